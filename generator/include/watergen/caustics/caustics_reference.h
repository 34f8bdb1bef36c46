// The CPU reference for caustics on a flat bottom under a wave surface (seed 002, section 6:
// photons cast from an orthographic camera along the sunlight, refracted through the surface,
// summed where they hit the bottom). Independent of the IR and of the shaders: its own wave
// model in double precision and many photons per texel, so that the GPU caustics passes can be
// measured against it.
//
// Intensity is the irradiance on the bottom relative to flat water without losses: 1 under
// flat water, above 1 where the surface focuses light, below where it spreads it. Photons are
// sampled on a regular grid over the surface's parameter plane (x, z) and each carries the
// flux its surface patch intercepts from a parallel beam, relative to the same patch flat:
// w = (dP/dz x dP/dx) . (-L) / (-L.y), and is splatted bilinearly where it lands. Over a whole
// period of the waves the weights average to exactly 1 (the beam's flux through a periodic surface
// equals that through its horizontal projection), so energy is conserved by construction and any
// loss is the losses asked for.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace watergen {

// One wave of seed 004's families: phase theta = frequency * (dir_x x + dir_z z) + phase;
// sum of sines: height amplitude * sin(theta); Gerstner also moves the point horizontally by
// steepness * amplitude * dir * cos(theta).
struct CausticsWave {
    double amplitude = 0, frequency = 0; // m, rad/m
    double dir_x = 1, dir_z = 0;         // unit direction of travel in xz
    double phase = 0;                    // rad (speed x time)
    double steepness = 0;                // Gerstner Q; 0: a sine wave
};

struct CausticsSetup {
    std::vector<CausticsWave> waves;
    std::array<double, 3> sun_direction{0, -1, 0}; // the way sunlight travels (y < 0)
    double ior = 1.333;                            // water; the seed refracts with 1/ior = 0.75
    double depth = 5;                              // bottom at y = -depth (m)
    // The bottom window the texture covers: [x0, x0 + size] x [z0, z0 + size], texel (i, j)
    // at row j (z), column i (x). Periodic: the window is a whole period of every wave, photons
    // are sampled over it and hits wrap around it. Otherwise photons are sampled over the window
    // grown by `margin` on every side, and hits outside the window are counted as lost.
    double x0 = 0, z0 = 0, size = 10;
    bool periodic = true;
    double margin = 0;
    uint32_t texels = 128;          // texture side
    uint32_t photons_per_side = 16; // photons per texel side: photons per texel = this squared
    bool fresnel = false;           // weight by the exact dielectric Fresnel transmittance
    double attenuation = 0;         // 1/m, along the refracted path: exp(-attenuation * length)
};

struct CausticsImage {
    uint32_t texels = 0;
    std::vector<double> intensity; // texels x texels, row-major (row = z)
    double weight_sampled = 0;     // mean photon weight before losses (1 over a period)
    double shadowed = 0;           // share of the surface facing away from the sun (weight < 0)
    double mean() const;           // area-weighted mean intensity over the window
    double max() const;
    double standard_deviation() const;
};

// The area-weighted mean of a texture's intensities (0 for none): what energy conservation is
// judged by, for the reference and the GPU passes alike.
double mean_intensity(const std::vector<double>& intensity);

// What:   the photon estimate of the caustics texture for `setup`.
// Cost:   (texels x photons_per_side)^2 photons, each a pass over the waves: 4M photons x 4
//         waves in about a second. Bad input (no texels, a sun not shining down, ior <= 1,
//         depth < 0) returns an empty image and the reason in *error.
CausticsImage caustics_reference(const CausticsSetup& setup, std::string* error);

// The CPU reference for the same values: seed 004's waves restated (a_i = A g_a^i,
// f_i = F g_f^i, phase t phi_i, Gerstner Q_i = Q / (f_i a_i n)), the sun, ior_water, the depth
// and window; not periodic, photons over the window grown by `margin`.
CausticsSetup caustics_reference_setup(const std::string& wave_model,
                                       const std::map<std::string, std::vector<double>>& values,
                                       uint32_t texels, double margin);

} // namespace watergen
