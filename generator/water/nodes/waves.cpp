// Wave models: sum of sines and Gerstner (004), 000's height-map march, and the search for
// the point where the view ray of the post-process pass meets the moving surface.
#include "watergen/water/nodes/waves.h"

#include <array>
#include <cstdint>
#include <memory>
#include <tuple>

#include "watergen/water/node_catalog.h"
#include "watergen/water/surface.h"

namespace watergen {

Expr safe_normalize(Expr v, Expr fallback) {
    Expr len2 = dot(v, v);
    // NaN compares false, so a NaN vector (a NaN texel upstream) takes the fallback as well.
    return select(len2 > 1e-30, v * rsqrt(max(len2, 1e-30)), fallback);
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

} // namespace

// ---- sum of sines ----

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

Expr heightmap_normal(Graph& g, Expr xz, Expr time) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "normals.heightmap_diff");
    Expr strength =
        uniform(g, {"heightmap_normal_strength", Type::Float, {1.0}, 0.0, 100.0, "", "000", ""});
    const Differences h = heightmap_differences(g, xz, time);
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

// ---- the water surface along the view ray ----

Expr search_relaxation(Graph& g, Expr view_ray, Expr max_slope) {
    FullPrecisionScope full(g);
    // |ray.y| is 0 for a horizontal ray (000's pitfall): the max() keeps the division finite,
    // which matters when max_slope is 0 (0 * inf = NaN). Rays pointing up get the same tiny
    // divisor and hence r ~ 0: they never reach the water.
    Expr ray_down = named(max(-view_ray.y(), 1e-6), "search_ray_down");
    Expr run = length(view_ray.xz());
    return named(1.0 / (1.0 + max_slope * run / ray_down), "search_relaxation");
}

WaveHit surface_search(const Surface& s, const SurfaceModel& model, int steps, int safe_steps,
                       Expr pixel_angle) {
    Graph& g = s.g;
    FullPrecisionScope full(g);
    // Along the ray, S(level) moves ray.xz / ray.y metres per metre of level, so the target
    // T(level) = water_level + h(S(level)) has T' = grad h . ray.xz / ray.y, |T'| <= G =
    // K |ray.xz| / |ray.y|. level += r (T - level) with r = 1 / (1 + G) has a derivative
    // 1 - r + r T' in [0, 2), never negative: started above every crest, the levels descend
    // monotonically onto the first crossing of the ray with the surface, never overshooting
    // into a later one (the plain iteration r = 1 oscillates, even chaotically, for grazing
    // rays). That is slow where G is large, so after `safe_steps` such steps each step is a
    // Newton step r = 1 / (1 - T') with T' from the model's analytic slope at S, kept within
    // [r_safe, 1] and within the bracket below. With the model band-limited
    // to the pixel footprint (pixel_angle) no pixel resolves the silhouettes of crests far
    // below its size, where the first crossing jumps: without the band limit, GPU and CPU
    // rounding sent a few grazing pixels to different crests.
    Expr r_safe = search_relaxation(g, s.view_ray, model.max_slope);
    Expr ray_down = max(-s.view_ray.y(), 1e-6); // guarded as in search_relaxation
    // Extent of the pixel on the water at distance t, along the view direction where the
    // grazing ray stretches it most (the band limit of the waves, see waves_at).
    auto footprint = [&](const PlaneHit& h) {
        return pixel_angle.valid() ? named(pixel_angle * h.distance / ray_down, "pixel_footprint")
                                   : Expr();
    };
    Expr level = named(s.level + model.top, "search_level");
    PlaneHit hit = intersect_plane(s, level);
    // The bracket [lo, hi] of the first crossing: hi is the last level found above the surface
    // (every safe step is), lo the last found below it (at first the bottom of the slab, where
    // T >= level holds for every model). A Newton step that leaves the bracket bisects it
    // instead: without that, a Newton step that overshoots a grazing crest can fall into a
    // 2-cycle between crest and trough (or a chaotic orbit) that 8 steps never leave, and
    // float rounding then picks the end of the orbit (measured up to 0.045 at 256x256).
    // The selects switch only where target = level (a root), where a Newton step lands on
    // the bracket's edge or where T' = 1; either way the step stays in a bracket that holds
    // the crossing, and the remaining steps converge into it from both branches.
    // A NaN height compares false everywhere and stays NaN (see set_water_column).
    Expr hi = level, lo = named(s.level - model.top, "search_low");
    for (int i = 0; i < steps; ++i) {
        Expr fp = footprint(hit);
        Expr target = named(s.level + model.height(hit.point.xz(), fp), "search_target");
        Expr r = r_safe;
        Expr t_slope;
        if (i >= safe_steps) {
            t_slope = -dot(model.slope(hit.point.xz(), fp), s.view_ray.xz()) / ray_down;
            Expr newton = 1.0 / max(1.0 - t_slope, 1e-6);
            r = named(clamp(newton, r_safe, constant(g, 1.0)), "search_step");
        }
        Expr f = target - level;
        Expr next = named(level + r * f, "search_level");
        if (i >= safe_steps) {
            Expr above = f < 0.0;
            hi = named(select(above, level, hi), "search_high");
            lo = named(select(above, lo, level), "search_low");
            // T' >= 1: Newton would step away from the bracket's crossing (towards one where
            // the ray leaves the surface); the clamped step r = 1 then expands errors by T'
            // per step (measured: float and double apart by 2x per step, 2.6e-4 at the end).
            Expr outside = (next < lo) || (next > hi) || (t_slope >= 1.0);
            next = named(select(outside, 0.5 * (lo + hi), next), "search_level");
        } else {
            hi = level; // a safe step never leaves the region above the first crossing
        }
        level = next;
        hit = intersect_plane(s, level);
    }
    return {hit.point, hit.distance, model.slope(hit.point.xz(), footprint(hit))};
}

namespace {

// Sum over the waves of a_i (the highest crest) and of a_i f_i (bounds |grad h|).
std::pair<Expr, Expr> wave_bounds(Graph& g, const WaveDefaults& d, Expr xz, Expr time) {
    Expr top, slope;
    for (const Wave& w : waves_at(g, d, xz, time)) {
        top = accumulate(top, w.amplitude);
        slope = accumulate(slope, w.amplitude * w.frequency);
    }
    return {top, slope};
}

} // namespace

SurfaceModel sum_of_sines_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.sum_of_sines");
    Expr zero = constant(g, {0.0, 0.0});
    auto [top, slope] = wave_bounds(g, sines_defaults(), zero, time);
    return {top, slope,
            [&g, time](Expr xz, Expr fp) { return sum_of_sines_height(g, xz, time, fp); },
            [&g, time](Expr xz, Expr fp) { return sum_of_sines_slope(g, xz, time, fp); }};
}

SurfaceModel gerstner_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.gerstner");
    Expr zero = constant(g, {0.0, 0.0});
    auto [top, slope] = wave_bounds(g, gerstner_defaults(), zero, time);
    Expr steepness =
        uniform(g, {"gerstner_steepness", Type::Float, {0.5}, 0.0, 1.0, "", "004", ""});
    // The height above world xz is the height of the grid point x0 with x0 + horizontal(x0)
    // = xz: one Newton step per search step refines x0 (gerstner_grid_newton). A fixed-point
    // step (a contraction by only Q) lagged metres behind when a grazing ray's S moved by
    // half a wavelength, so the search saw heights and slopes of the wrong place.
    // The height is corrected to first order for the step's remaining miss (S minus the
    // displaced x0, up to metres while S still moves) with the world slope at x0, which the
    // Newton steps of the search compute anyway: without that, a height from a stale x0 put
    // the search's bracket on the wrong side of the surface (residuals up to 1.3 cm on rays
    // 20 degrees down). Crests bunch the grid by up to 1 / (1 - Q), which steepens the world
    // slope by as much. Height and slope at the same S share one step.
    struct Grid {
        Expr x0;
        uint32_t xz = UINT32_MAX;
    };
    auto state = std::make_shared<Grid>();
    auto grid = [&g, time, state](Expr xz, Expr fp) {
        if (state->xz != xz.id()) {
            FullPrecisionScope full(g);
            OriginScope scope(g, "waves.gerstner");
            state->x0 = gerstner_grid_newton(g, xz, time, state->x0.valid() ? state->x0 : xz, fp);
            state->xz = xz.id();
        }
        return state->x0;
    };
    auto world_slope = [&g, time](Expr x0, Expr fp) {
        Expr n = gerstner_normal(g, x0, time, fp);
        // dh/dx = -n.x / n.y; n.y > 0 unless a steepness-1 crest folds, where the
        // max() caps the slope instead of dividing by zero.
        return named(-n.xz() / max(n.y(), 1e-4), "wave_slope");
    };
    return {top, named(slope / max(1.0 - steepness, 0.2), "gerstner_max_slope"),
            [&g, time, grid, world_slope](Expr xz, Expr fp) {
                Expr x0 = grid(xz, fp);
                Expr d = gerstner_displacement(g, x0, time, fp);
                FullPrecisionScope full(g);
                OriginScope scope(g, "waves.gerstner");
                Expr miss = xz - (x0 + d.swizzle("xz"));
                return named(d.y() + dot(world_slope(x0, fp), miss), "gerstner_height");
            },
            [grid, world_slope](Expr xz, Expr fp) { return world_slope(grid(xz, fp), fp); }};
}

SurfaceModel heightmap_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.heightmap_march");
    Expr amplitude = uniform(g, heightmap_amplitude());
    Expr scale =
        uniform(g, {"heightmap_scale", Type::Float, {0.06}, 1e-4, 100.0, "1/m", "000", ""});
    // A property of the texture: the largest |grad| of its values per tile (the scene's map
    // stays under 2 pi sum |w| |(m, n)| = 17.52, see render/scene_wave_inputs.cpp).
    Expr gradient =
        uniform(g, {"heightmap_max_gradient", Type::Float, {17.6}, 0.0, 1e4, "1/tile", "000", ""});
    return {amplitude, named(amplitude * scale * gradient, "heightmap_max_slope"),
            [&g, time](Expr xz, Expr fp) { return heightmap_height(g, xz, time, fp); },
            [&g, time](Expr xz, Expr fp) { return heightmap_slope(g, xz, time, fp); }};
}

WaveHit find_wave_surface(const Surface& s, const std::string& choice, Expr pixel_angle) {
    Graph& g = s.g;
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves." + choice);
    if (choice == "sum_of_sines")
        return surface_search(s, sum_of_sines_surface(g, s.time), kWaveSurfaceSteps,
                              kWaveSurfaceSafeSteps, pixel_angle);
    if (choice == "gerstner")
        return surface_search(s, gerstner_surface(g, s.time), kWaveSurfaceSteps,
                              kWaveSurfaceSafeSteps, pixel_angle);
    if (choice == "heightmap_march")
        return surface_search(s, heightmap_surface(g, s.time), kHeightmapMarchSteps,
                              kHeightmapMarchSafeSteps, pixel_angle);
    if (choice == "heightmap_march_converged")
        return surface_search(s, heightmap_surface(g, s.time), kHeightmapMarchConvergedSteps,
                              kHeightmapMarchConvergedSafeSteps, pixel_angle);
    if (choice != "flat") g.error("waves: no node for choice '" + choice + "'");
    const PlaneHit hit = intersect_plane(s, s.level);
    return {hit.point, hit.distance, constant(g, {0.0, 0.0})};
}

void apply_waves(Surface& s, const std::string& choice) {
    OriginScope scope(s.g, "waves." + choice);
    if (choice == "flat") {
        const PlaneHit hit = intersect_plane(s, s.level);
        s.surface_point = hit.point;
        set_water_column(s, hit.distance);
        return;
    }
    if (choice == "sum_of_sines" || choice == "gerstner" || choice == "heightmap_march" ||
        choice == "heightmap_march_converged") {
        // Radians per pixel (view_ray is unit): the band limit of every wave model's search.
        Expr pixel_angle =
            named(max(length(ddx(s.view_ray)), length(ddy(s.view_ray))), "pixel_angle");
        const WaveHit hit = find_wave_surface(s, choice, pixel_angle);
        s.surface_point = hit.point;
        set_water_column(s, hit.distance);
        s.wave_slope = hit.slope;
        return;
    }
    s.g.error("waves: no node for choice '" + choice + "'");
}

void append_waves_nodes(std::vector<CatalogNode>& list) {
    // The axis choices: where a view ray from `eye` meets the water -> (point, distance).
    for (const char* choice :
         {"flat", "sum_of_sines", "gerstner", "heightmap_march", "heightmap_march_converged"}) {
        const std::string name = choice;
        const bool textured = name.rfind("heightmap", 0) == 0;
        list.push_back(
            {"waves." + name,
             std::string(
                 "surface point and ray distance (vec4) where the view ray meets the water") +
                 (textured ? "; reads texture height_map" : ""),
             {{"eye", Type::Vec3},
              {"view_ray", Type::Vec3},
              {"level", Type::Float},
              {"time", Type::Float}},
             [name](Graph& g, const std::vector<Expr>& in) {
                 FullPrecisionScope full(g); // points 5e6 m away overflow half
                 Surface s(g);
                 s.eye = in[0];
                 s.view_ray = in[1];
                 s.level = in[2];
                 s.time = in[3];
                 const WaveHit hit = find_wave_surface(s, name);
                 return vec4(hit.point, hit.distance);
             }});
    }
    // Full detail (no footprint): the catalog evaluates points, not pixels.
    using Fn = Expr (*)(Graph&, Expr, Expr, Expr);
    const Fn heightmap = [](Graph& g, Expr xz, Expr time, Expr) {
        return heightmap_height(g, xz, time);
    };
    for (auto [name, f, what] :
         {std::tuple{"waves.sum_of_sines.height", Fn(&sum_of_sines_height),
                     "height above the water level at xz, m"},
          std::tuple{"waves.sum_of_sines.slope", Fn(&sum_of_sines_slope), "(dh/dx, dh/dz) at xz"},
          std::tuple{"waves.sum_of_sines.normal", Fn(&sum_of_sines_normal), "unit normal at xz"},
          std::tuple{"waves.gerstner.displacement", Fn(&gerstner_displacement),
                     "displacement of grid point xz, m"},
          std::tuple{"waves.gerstner.normal", Fn(&gerstner_normal),
                     "exact unit normal at grid point xz"},
          std::tuple{"waves.gerstner.normal_gpugems", Fn(&gerstner_normal_gpugems),
                     "GPU Gems' closed-form normal at grid point xz"},
          std::tuple{"waves.heightmap.height", heightmap,
                     "height-map height at xz, m; reads texture height_map"}})
        list.push_back(
            {name,
             what,
             {{"xz", Type::Vec2}, {"time", Type::Float}},
             [f](Graph& g, const std::vector<Expr>& in) { return f(g, in[0], in[1], Expr()); }});
}

} // namespace watergen
