// The caustics passes, generated from the same wave nodes as the water shader: a grid over the
// water surface, each grid point moved to where the sunlight refracted through the surface
// meets a flat bottom, drawn into the caustics texture with additive blending.
// - area_ratio (Evan Wallace's method, as Unity HDRP's water ships it): the grid's triangles;
//   each fragment adds its triangle's area ratio, old (the beam's cross-section, projected
//   along the light onto the water plane) over new (on the bottom), clamped to
//   caustics_clamp. Overlapping (folded) triangles add up, as the light they carry does.
// - photon_splat (seed 002, section 6): the grid's points as photons, each adding the light
//   its patch of surface intercepts to the texel it lands in (the seed sums on the CPU; here
//   the GPU's blending sums).
// Both stages are DSL graphs, emitted and validated like the water pass.
#pragma once

#include <optional>
#include <string>

#include "watergen/ir/core/ir.h"

namespace watergen {

enum class CausticsMethod { AreaRatio, PhotonSplat };

// How far beyond the window the grid must reach, m, for a bottom `depth` m down: sunlight drifts
// sideways through the water by up to ~1.1 x depth (a low sun's refraction, at most
// tan(asin(1 / 1.333)) = 1.13, plus the waves' slopes), and 1 m for the waves' horizontal
// displacement. The build's draw description (`margin`) states the same scale and offset.
inline constexpr double kCausticsMarginPerDepth = 1.2;
inline constexpr double kCausticsMarginAdd = 1.0;
constexpr double caustics_margin(double depth) {
    return kCausticsMarginPerDepth * depth + kCausticsMarginAdd;
}

const char* to_string(CausticsMethod method);
// The pass a caustics choice of the water shader reads: area_ratio and photon_splat; nullopt
// for none and texture (no pass).
std::optional<CausticsMethod> caustics_pass_method(const std::string& caustics_choice);
// The vertex skeleton under templates/<lang>/: "caustics" or "caustics_photons".
const char* caustics_skeleton(CausticsMethod method);

struct CausticsPass {
    CausticsMethod method = CausticsMethod::AreaRatio;
    std::string wave_model; // "sum_of_sines" or "gerstner"
    // Attribute grid_xz (vec2: the undisplaced grid point, m); outputs position (Vulkan clip
    // space of the caustics texture) and, for area_ratio, landing (vec2, where the ray meets
    // the bottom, m), offset (vec2, the beam point minus the landing point, m) and clamp
    // (caustics_clamp); for photon_splat, weight (the photon's light in texel units).
    Graph vertex;
    // Reads no parameter: area_ratio's varyings v_landing, v_offset, v_clamp, photon_splat's
    // v_weight. Output color (vec4: the light added in rgb, 1 in a).
    Graph fragment;
};

// Parameters beside the wave model's and the water pass's (time, sun_direction, ior_water):
// caustics_depth (m, the bottom below the water level), caustics_window (vec3: the bottom window
// x0, z0 and size the texture covers, m); area_ratio's caustics_clamp (the largest ratio a
// fragment adds; HDRP's 5), photon_splat's caustics_photon_share (grid cell area over texel
// area). An unknown model records a diagnostic on the vertex graph.
CausticsPass build_caustics_pass(CausticsMethod method, const std::string& wave_model);

} // namespace watergen
