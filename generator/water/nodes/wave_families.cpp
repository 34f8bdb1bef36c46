// Wave families: sum of sines and Gerstner (004) and 000's height map: heights, slopes,
// normals and the bounds the surface search (waves.cpp) needs.
#include "watergen/water/nodes/waves.h"

#include <array>

namespace watergen {

Expr safe_normalize(Expr v, Expr fallback) {
    Expr len2 = dot(v, v);
    // NaN compares false, so a NaN vector (a NaN texel upstream) takes the fallback as well.
    return select(len2 > 1e-30, v * rsqrt(max(len2, 1e-30)), fallback);
}

Expr robust_normalize(Expr v, Expr fallback) {
    Expr a = abs(v);
    Expr largest = max(max(a.x(), a.y()), a.z());
    // NaN compares false: a NaN vector keeps its NaN scale and safe_normalize takes the fallback.
    return safe_normalize(v / max(largest, 1e-30), fallback);
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// Defaults of one wave family. 004 multiplies frequency by 1.18 and amplitude by 0.82 per
// wave; directions are unit xz vectors (not normalised in the shader, so a zero direction only
// freezes that wave in space); phase speeds follow deep-water dispersion, sqrt(9.81 f_i).
struct WaveDefaults {
    const char* family; // parameter prefix
    double amplitude, frequency;
    std::vector<double> directions_a, directions_b, phase_speeds;
};

const WaveDefaults& sines_defaults() {
    static const WaveDefaults d{"waves",
                                0.15,
                                0.9,
                                {0.28, -0.96, -0.6, -0.8},
                                {0.8, -0.6, -0.96, -0.28},
                                {2.97, 3.23, 3.51, 3.81}};
    return d;
}

const WaveDefaults& gerstner_defaults() {
    static const WaveDefaults d{"gerstner",
                                0.2,
                                0.7,
                                {0.0, -1.0, 0.6, -0.8},
                                {-0.8, -0.6, 0.96, -0.28},
                                {2.62, 2.85, 3.09, 3.36}};
    return d;
}

struct Wave {
    Expr amplitude, frequency, direction, theta;
    Expr fade; // band limit in [0, 1]; invalid: the wave in full
    Expr faded(Expr e) const { return fade.valid() ? e * fade : e; }
};

std::array<Wave, kWaveCount> waves_at(Graph& g, const WaveDefaults& d, Expr xz, Expr time,
                                      Expr footprint = Expr()) {
    const std::string f = d.family;
    Expr amplitude =
        uniform(g, {f + "_amplitude", Type::Float, {d.amplitude}, 0.0, 10.0, "m", "004", ""});
    Expr frequency =
        uniform(g, {f + "_frequency", Type::Float, {d.frequency}, 1e-3, 100.0, "rad/m", "004", ""});
    Expr amplitude_gain =
        uniform(g, {f + "_amplitude_gain", Type::Float, {0.82}, 0.1, 2.0, "", "004", ""});
    Expr frequency_gain =
        uniform(g, {f + "_frequency_gain", Type::Float, {1.18}, 0.1, 4.0, "", "004", ""});
    Expr dirs_a =
        uniform(g, {f + "_directions_a", Type::Vec4, d.directions_a, -1.0, 1.0, "", "004", ""});
    Expr dirs_b =
        uniform(g, {f + "_directions_b", Type::Vec4, d.directions_b, -1.0, 1.0, "", "004", ""});
    Expr speeds = uniform(
        g, {f + "_phase_speeds", Type::Vec4, d.phase_speeds, -100.0, 100.0, "rad/s", "004", ""});
    const std::array<Expr, kWaveCount> dirs = {dirs_a.xy(), dirs_a.swizzle("zw"), dirs_b.xy(),
                                               dirs_b.swizzle("zw")};
    const std::array<Expr, kWaveCount> phis = {speeds.x(), speeds.y(), speeds.z(), speeds.w()};
    std::array<Wave, kWaveCount> out;
    for (int i = 0; i < kWaveCount; ++i) {
        if (i > 0) {
            amplitude = amplitude * amplitude_gain;
            frequency = frequency * frequency_gain;
        }
        // A pixel holds no wave shorter than two footprints (Nyquist): fade wave i out as its
        // wavelength 2 pi / f_i drops from 4 to 2 footprints, i.e. f_i fp from pi / 2 to pi.
        Expr fade;
        if (footprint.valid())
            fade = named(saturate(2.0 - frequency * footprint * (2.0 / kPi)), "wave_fade");
        Expr theta = named(frequency * dot(dirs[i], xz) + time * phis[i], "wave_theta");
        out[i] = {amplitude, frequency, dirs[i], theta, fade};
    }
    return out;
}

Expr accumulate(Expr sum, Expr term) {
    return sum.valid() ? sum + term : term;
}

Expr up(Graph& g) {
    return constant(g, {0.0, 1.0, 0.0});
}

struct GerstnerWave {
    Expr horizontal; // Q_i A_i, m (band-limited)
    Expr amplitude;  // A_i, m (band-limited)
    Expr frequency, direction, s, c;
};

std::array<GerstnerWave, kWaveCount> gerstner_waves(Graph& g, Expr grid_xz, Expr time,
                                                    Expr footprint) {
    Expr steepness =
        uniform(g, {"gerstner_steepness", Type::Float, {0.5}, 0.0, 1.0, "", "004", ""});
    std::array<GerstnerWave, kWaveCount> out;
    const auto waves = waves_at(g, gerstner_defaults(), grid_xz, time, footprint);
    for (int i = 0; i < kWaveCount; ++i) {
        const Wave& w = waves[i];
        // GPU Gems: Q_i = Q / (w_i A_i n) keeps sum_i w_i Q_i A_i = Q <= 1, so crests never loop.
        // Amplitude 0 would make Q_i = inf and Q_i A_i = inf * 0 = NaN; the max() keeps Q_i
        // finite and Q_i A_i -> 0 with A_i (no horizontal motion without a wave).
        Expr q = named(steepness / (double(kWaveCount) * max(w.frequency * w.amplitude, 1e-6)),
                       "gerstner_q");
        // The band limit fades the orbit as a whole, horizontal motion included.
        out[i] = {w.faded(named(q * w.amplitude, "gerstner_qa")),
                  w.faded(w.amplitude),
                  w.frequency,
                  w.direction,
                  named(sin(w.theta), "gerstner_sin"),
                  named(cos(w.theta), "gerstner_cos")};
    }
    return out;
}

Expr gerstner_horizontal(Graph& g, Expr grid_xz, Expr time, Expr footprint) {
    Expr sum;
    for (const auto& w : gerstner_waves(g, grid_xz, time, footprint))
        sum = accumulate(sum, w.horizontal * w.c * w.direction);
    return sum;
}

// Sum over the waves of a_i (the highest crest) and of a_i f_i (bounds |grad h|).
WaveBounds wave_bounds(Graph& g, const WaveDefaults& d, Expr xz, Expr time) {
    Expr top, slope;
    for (const Wave& w : waves_at(g, d, xz, time)) {
        top = accumulate(top, w.amplitude);
        slope = accumulate(slope, w.amplitude * w.frequency);
    }
    return {top, slope};
}

} // namespace

// ---- sum of sines ----

WaveBounds sum_of_sines_bounds(Graph& g, Expr time) {
    return wave_bounds(g, sines_defaults(), constant(g, {0.0, 0.0}), time);
}

Expr sum_of_sines_height(Graph& g, Expr xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.sum_of_sines");
    Expr h;
    for (const Wave& w : waves_at(g, sines_defaults(), xz, time, footprint))
        h = accumulate(h, w.faded(w.amplitude) * sin(w.theta));
    return named(h, "wave_height");
}

Expr sum_of_sines_slope(Graph& g, Expr xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.sum_of_sines");
    // d/dp of a sin(f (d . p) + t phi) = a f cos(...) d.
    Expr slope;
    for (const Wave& w : waves_at(g, sines_defaults(), xz, time, footprint))
        slope =
            accumulate(slope, (w.faded(w.amplitude) * w.frequency * cos(w.theta)) * w.direction);
    return named(slope, "wave_slope");
}

Expr sum_of_sines_normal(Graph& g, Expr xz, Expr time, Expr footprint) {
    Expr slope = sum_of_sines_slope(g, xz, time, footprint);
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.sum_of_sines");
    // The y component is 1, so the vector never vanishes: a plain normalize is safe.
    return named(normalize(vec3(-slope.x(), constant(g, 1.0), -slope.y())), "wave_normal");
}

// ---- Gerstner ----

Expr gerstner_displacement(Graph& g, Expr grid_xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    Expr horizontal, height;
    for (const auto& w : gerstner_waves(g, grid_xz, time, footprint)) {
        horizontal = accumulate(horizontal, w.horizontal * w.c * w.direction);
        height = accumulate(height, w.amplitude * w.s);
    }
    return named(vec3(horizontal.x(), height, horizontal.y()), "gerstner_displacement");
}

Expr gerstner_normal(Graph& g, Expr grid_xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    // dP/dx = (1,0,0) + sum_i D_i.x e_i and dP/dz = (0,0,1) + sum_i D_i.z e_i with
    // e_i = (-k_i D_i.x, m_i, -k_i D_i.z), k_i = Q_i A_i w_i sin th_i, m_i = A_i w_i cos th_i.
    Expr tx = constant(g, {1.0, 0.0, 0.0}), tz = constant(g, {0.0, 0.0, 1.0});
    for (const auto& w : gerstner_waves(g, grid_xz, time, footprint)) {
        Expr k = w.horizontal * w.frequency * w.s;
        Expr m = w.amplitude * w.frequency * w.c;
        Expr e = vec3(-k * w.direction.x(), m, -k * w.direction.y());
        tx = tx + w.direction.x() * e;
        tz = tz + w.direction.y() * e;
    }
    // The tangents are parallel only where a steepness-1 crest folds (dP/dx = 0): keep up.
    return named(safe_normalize(cross(tz, tx), up(g)), "gerstner_normal");
}

Expr gerstner_normal_gpugems(Graph& g, Expr grid_xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    // GPU Gems ch. 1, eq. 12: N = (-sum D.x w A C, 1 - sum Q w A S, -sum D.z w A C). It drops
    // the products between different waves that the exact cross product keeps (exact for one
    // wave); evaluated here at the grid point, like the exact normal, to isolate that error.
    Expr xz, y;
    for (const auto& w : gerstner_waves(g, grid_xz, time, footprint)) {
        xz = accumulate(xz, (w.amplitude * w.frequency * w.c) * w.direction);
        y = accumulate(y, w.horizontal * w.frequency * w.s);
    }
    return named(safe_normalize(vec3(-xz.x(), 1.0 - y, -xz.y()), up(g)), "gerstner_normal_gpugems");
}

Expr gerstner_grid_point(Graph& g, Expr world_xz, Expr time, Expr start, int iterations,
                         Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    Expr x0 = start;
    for (int i = 0; i < iterations; ++i)
        x0 = named(world_xz - gerstner_horizontal(g, x0, time, footprint), "gerstner_grid_point");
    return x0;
}

WaveBounds gerstner_bounds(Graph& g, Expr time) {
    return wave_bounds(g, gerstner_defaults(), constant(g, {0.0, 0.0}), time);
}

// One Newton step towards the grid point x0 with x0 + horizontal(x0) = world_xz, from x0.
// The Jacobian J = I - sum_i k_i D_i D_i^T (k_i = Q_i A_i w_i sin th_i) is symmetric with
// eigenvalues in [1 - Q, 1 + Q] for unit directions; its determinant is floored (a damped step
// where a steep crest nearly folds) so the step stays finite and continuous in its inputs.
// Same sines and cosines as the displacement and normal at x0: no extra transcendentals.
Expr gerstner_grid_newton(Graph& g, Expr world_xz, Expr time, Expr x0, Expr footprint) {
    Expr horizontal, jxx, jxz, jzz;
    for (const auto& w : gerstner_waves(g, x0, time, footprint)) {
        horizontal = accumulate(horizontal, w.horizontal * w.c * w.direction);
        Expr k = w.horizontal * w.frequency * w.s;
        Expr kx = k * w.direction.x();
        jxx = accumulate(jxx, kx * w.direction.x());
        jxz = accumulate(jxz, kx * w.direction.y());
        jzz = accumulate(jzz, (k * w.direction.y()) * w.direction.y());
    }
    jxx = 1.0 - jxx;
    jzz = 1.0 - jzz;
    jxz = -jxz;
    Expr f = named(x0 + horizontal - world_xz, "gerstner_grid_residual");
    Expr det = named(max(jxx * jzz - jxz * jxz, 0.04), "gerstner_grid_det");
    Expr step = vec2(jzz * f.x() - jxz * f.y(), jxx * f.y() - jxz * f.x()) / det;
    return named(x0 - step, "gerstner_grid_point");
}

// ---- height map ----

Parameter heightmap_amplitude() {
    return {"heightmap_amplitude", Type::Float, {0.3}, 0.0, 10.0, "m", "000", ""};
}

TextureInput height_map_texture() {
    return {"height_map", Type::Texture2D,
            "wave height in r, [-1, 1]; periodic tile, texel k at k / (n - 1)", ""};
}

Expr tile_coordinate(Expr uv, Expr texels) {
    // Texel centre k sits at (k + 0.5) / n; tile coordinate c in [0, 1) maps to k = c (n - 1).
    // The tile's last texel repeats its first, so the wrap is seamless with a clamp sampler.
    return (fract(uv) * (texels - 1.0) + 0.5) / texels;
}

Expr heightmap_height(Graph& g, Expr xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    // Shared by the march and the height-map normals: the caller's feature node owns it.
    OriginScope scope(g, g.origin().empty() ? "waves.heightmap" : g.origin());
    Expr amplitude = uniform(g, heightmap_amplitude());
    Expr scale =
        uniform(g, {"heightmap_scale", Type::Float, {0.06}, 1e-4, 100.0, "1/m", "000", ""});
    Expr scroll =
        uniform(g, {"heightmap_scroll", Type::Vec2, {0.01, -0.02}, -10.0, 10.0, "1/s", "000", ""});
    Expr texels =
        uniform(g, {"heightmap_texels", Type::Float, {64.0}, 2.0, 16384.0, "texels", "000", ""});
    Expr uv = xz * scale + time * scroll;
    // Level 0 explicitly: the tile wrap makes implicit derivatives jump at seams, and a
    // vertex stage or a probe has none.
    Expr b = sample_level(texture(g, height_map_texture()), tile_coordinate(uv, texels),
                          constant(g, 0.0))
                 .x();
    if (footprint.valid()) {
        // Without mip levels the map can only fade as a whole: by its highest frequency
        // (heightmap_max_cycles per tile), between 4 and 2 footprints per wavelength as the
        // analytic waves do (waves_at).
        Expr cycles =
            uniform(g, {"heightmap_max_cycles", Type::Float, {3.7}, 0.0, 1e4, "1/tile", "000", ""});
        amplitude =
            amplitude * named(saturate(2.0 - 4.0 * cycles * scale * footprint), "heightmap_fade");
    }
    return named(amplitude * b, "heightmap_height");
}

namespace {

struct Differences {
    Expr west, east, south, north, offset;
};

Differences heightmap_differences(Graph& g, Expr xz, Expr time, Expr footprint = Expr()) {
    Expr d =
        uniform(g, {"heightmap_normal_offset", Type::Float, {0.25}, 0.0, 10.0, "m", "000", ""});
    Expr zero = constant(g, 0.0);
    Expr dx = vec2(d, zero), dz = vec2(zero, d);
    return {heightmap_height(g, xz - dx, time, footprint),
            heightmap_height(g, xz + dx, time, footprint),
            heightmap_height(g, xz - dz, time, footprint),
            heightmap_height(g, xz + dz, time, footprint), d};
}

} // namespace

Expr heightmap_normal(Graph& g, Expr xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "normals.heightmap_diff");
    Expr strength =
        uniform(g, {"heightmap_normal_strength", Type::Float, {1.0}, 0.0, 100.0, "", "000", ""});
    const Differences h = heightmap_differences(g, xz, time, footprint);
    // 000: N = {W - E, 2d, S - N}. With d = 0 (or a flat map and strength 0 at d = 0) the vector
    // is zero: safe_normalize keeps the plane's normal instead of NaN.
    Expr n = vec3((h.west - h.east) * strength, 2.0 * h.offset, (h.south - h.north) * strength);
    return named(safe_normalize(n, up(g)), "heightmap_normal");
}

Expr heightmap_slope(Graph& g, Expr xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.heightmap_march");
    const Differences h = heightmap_differences(g, xz, time, footprint);
    Expr two_d = max(2.0 * h.offset, 1e-6); // offset 0 is allowed: no division by zero
    return named(vec2(h.east - h.west, h.north - h.south) / two_d, "heightmap_slope");
}

} // namespace watergen
