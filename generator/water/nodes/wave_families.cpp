// Wave families: sum of sines and Gerstner (004) and 000's height map: heights, slopes,
// normals and the bounds the surface search (waves.cpp) needs.
#include "watergen/water/nodes/waves.h"

#include "watergen/water/frame.h"

#include <functional>
#include <string>
#include <vector>

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
// freezes that wave in space); phase speeds follow deep-water dispersion, sqrt(9.81 f_i). The
// first kDefaultWaveCount waves are 004's; the rest continue the series in new directions.
struct WaveDefaults {
    const char* family;               // parameter prefix
    double amplitude, frequency;      // A, F
    std::vector<double> directions;   // (x, z) per wave, kMaxWaves of them
    std::vector<double> phase_speeds; // rad/s per wave
};

const WaveDefaults& sines_defaults() {
    static const WaveDefaults d{"waves",
                                0.15,
                                0.9,
                                {0.28, -0.96, -0.6, -0.8, 0.8, -0.6, -0.96, -0.28, 0.6, -0.8, -0.8,
                                 -0.6, 0.96, -0.28, -0.28, -0.96},
                                {2.97, 3.23, 3.51, 3.81, 4.14, 4.49, 4.88, 5.30}};
    return d;
}

const WaveDefaults& gerstner_defaults() {
    static const WaveDefaults d{"gerstner",
                                0.2,
                                0.7,
                                {0.0, -1.0, 0.6, -0.8, -0.8, -0.6, 0.96, -0.28, -0.6, -0.8, 0.8,
                                 -0.6, -0.28, -0.96, 0.28, -0.96},
                                {2.62, 2.85, 3.09, 3.36, 3.65, 3.96, 4.30, 4.68}};
    return d;
}

// A specialization constant: an engine fixes its wave count when it builds the pipeline, and the
// driver then knows the loops' trip count and unrolls them (UnrollHint::Driver). Read from the
// uniform block, the count keeps every wave loop a real loop: on lavapipe the Gerstner search drew
// 2.4x the instructions (watergen cost --waves gerstner --size 64: 22.0M against 9.3M).
Parameter wave_count(const WaveDefaults& d) {
    Parameter p{.name = std::string(d.family) + "_wave_count",
                .type = Type::Float,
                .default_value = {double(kDefaultWaveCount)},
                .max = double(kMaxWaves),
                .seed = "004"};
    p.specialization = true;
    return p;
}

Parameter wave_array(const WaveDefaults& d, const char* name, Type type,
                     const std::vector<double>& values, double lo, double hi, const char* unit) {
    Parameter p{.name = std::string(d.family) + name,
                .type = type,
                .default_value = values,
                .min = lo,
                .max = hi,
                .unit = unit,
                .seed = "004"};
    p.array_size = kMaxWaves;
    return p;
}

struct Wave {
    Expr amplitude, frequency, direction, theta;
    Expr fade; // band limit in [0, 1]; invalid: the wave in full
    Expr faded(Expr e) const { return fade.valid() ? e * fade : e; }
};

// Wave i's terms added to the sums so far: the next sums, in the same order.
using WaveTerms = std::function<std::vector<Expr>(const Wave&, const std::vector<Expr>& sums)>;

// The sums over a family's waves at xz (`initial`, then each wave's terms in wave order) in one
// loop of <family>_wave_count iterations. The loop carries 004's geometric series: each wave's
// amplitude and frequency times the gains give the next wave's, in the order the unrolled sums
// multiplied them, so the float arithmetic is theirs. Inside a search step the loop runs in
// that step's body (the graph of xz).
std::vector<Expr> sum_over_waves(Graph& g, const WaveDefaults& d, Expr xz, Expr time,
                                 Expr footprint, const std::vector<Expr>& initial,
                                 const WaveTerms& terms) {
    const std::string f = d.family;
    std::vector<Expr> carried = {uniform(g, {.name = f + "_amplitude",
                                             .type = Type::Float,
                                             .default_value = {d.amplitude},
                                             .max = 10.0,
                                             .unit = "m",
                                             .seed = "004"}),
                                 uniform(g, {.name = f + "_frequency",
                                             .type = Type::Float,
                                             .default_value = {d.frequency},
                                             .min = 1e-3,
                                             .max = 100.0,
                                             .unit = "rad/m",
                                             .seed = "004"})};
    carried.insert(carried.end(), initial.begin(), initial.end());
    Expr amplitude_gain = uniform(g, {.name = f + "_amplitude_gain",
                                      .type = Type::Float,
                                      .default_value = {0.82},
                                      .min = 0.1,
                                      .max = 2.0,
                                      .seed = "004"});
    Expr frequency_gain = uniform(g, {.name = f + "_frequency_gain",
                                      .type = Type::Float,
                                      .default_value = {1.18},
                                      .min = 0.1,
                                      .max = 4.0,
                                      .seed = "004"});
    const Parameter directions =
        wave_array(d, "_wave_directions", Type::Vec2, d.directions, -1.0, 1.0, "");
    const Parameter speeds =
        wave_array(d, "_wave_speeds", Type::Float, d.phase_speeds, -100.0, 100.0, "rad/s");
    // With the scene's clock, xz is in the frame (frame.h) and wave i's phase is f_i (d_i . xz)
    // plus its offset f_i (d_i . c) + s_i t from the host, reduced into [-pi, pi): the float
    // phase stays within f_i times the distance from the frame centre at any time and place.
    // A catalog node's time and world xz go in as given.
    const bool framed = is_scene_clock(time);
    const Parameter phases = wave_phase_offsets(f, kMaxWaves);
    if (framed) { // declared in the block the loop body reads them from
        uniform(g, phases);
        g.declare_parameter(speeds); // the host reads it
    }
    Graph& where = xz.graph();
    FullPrecisionScope full(where);
    const auto sums = loop(
        where, uniform(g, wave_count(d)), kMaxWaves, carried,
        [&](Expr i, const std::vector<Expr>& c) {
            Wave w{c[0], c[1], element(directions, i), Expr(), Expr()};
            // A pixel holds no wave shorter than two footprints (Nyquist): fade wave i out as its
            // wavelength 2 pi / f_i drops from 4 to 2 footprints, i.e. f_i fp from pi / 2 to pi.
            if (footprint.valid())
                w.fade = named(saturate(2.0 - w.frequency * footprint * (2.0 / kPi)), "wave_fade");
            w.theta = named(w.frequency * dot(w.direction, xz) +
                                (framed ? element(phases, i) : time * element(speeds, i)),
                            "wave_theta");
            std::vector<Expr> next = {c[0] * amplitude_gain, c[1] * frequency_gain};
            const std::vector<Expr> added = terms(w, std::vector<Expr>(c.begin() + 2, c.end()));
            next.insert(next.end(), added.begin(), added.end());
            return LoopStep{next, Expr()};
        },
        LoopOptions{UnrollHint::Driver});
    return std::vector<Expr>(sums.begin() + 2, sums.end());
}

Expr up(Graph& g) {
    return constant(g, {0.0, 1.0, 0.0});
}

Expr zero2(Graph& g) {
    return constant(g, {0.0, 0.0});
}

// Sum over the waves of a_i (the highest crest) and of a_i f_i (bounds |grad h|).
WaveBounds wave_bounds(Graph& g, const WaveDefaults& d, Expr time) {
    const auto sums = sum_over_waves(
        g, d, zero2(g), time, Expr(), {constant(g, 0.0), constant(g, 0.0)},
        [](const Wave& w, const std::vector<Expr>& s) {
            return std::vector<Expr>{s[0] + w.amplitude, s[1] + w.amplitude * w.frequency};
        });
    return {sums[0], sums[1]};
}

struct GerstnerWave {
    Expr horizontal; // Q_i A_i, m (band-limited)
    Expr amplitude;  // A_i, m (band-limited)
    Expr frequency, direction, s, c;
};

using GerstnerTerms =
    std::function<std::vector<Expr>(const GerstnerWave&, const std::vector<Expr>& sums)>;

std::vector<Expr> sum_over_gerstner_waves(Graph& g, Expr grid_xz, Expr time, Expr footprint,
                                          const std::vector<Expr>& initial,
                                          const GerstnerTerms& terms) {
    Expr steepness = uniform(g, gerstner_steepness());
    // n, the waves summed (the loop runs no wave when floor(count) < 1).
    Expr n = min(floor(uniform(g, wave_count(gerstner_defaults()))), double(kMaxWaves));
    auto wave = [&](const Wave& w, const std::vector<Expr>& sums) {
        // GPU Gems: Q_i = Q / (w_i A_i n) keeps sum_i w_i Q_i A_i = Q <= 1, so crests never
        // loop. Amplitude 0 would make Q_i = inf and Q_i A_i = inf * 0 = NaN; the max() keeps
        // Q_i finite and Q_i A_i -> 0 with A_i (no horizontal motion without a wave).
        Expr q = steepness / (n * max(w.frequency * w.amplitude, 1e-6));
        // The band limit fades the orbit as a whole, horizontal motion included.
        const GerstnerWave gw{w.faded(q * w.amplitude),
                              w.faded(w.amplitude),
                              w.frequency,
                              w.direction,
                              named(sin(w.theta), "gerstner_sin"),
                              named(cos(w.theta), "gerstner_cos")};
        return terms(gw, sums);
    };
    return sum_over_waves(g, gerstner_defaults(), grid_xz, time, footprint, initial, wave);
}

// The Gerstner sums a caller asks for, from one loop.
enum GerstnerSum : unsigned {
    kHorizontal = 1,   // sum Q_i A_i cos th_i D_i (vec2)
    kDisplacement = 2, // the same with sum A_i sin th_i between its components (vec3, P - x0)
    kTangents = 4,     // dP/dx and dP/dz
    kJacobian = 8,     // sum k_i D_i D_i^T, k_i = Q_i A_i w_i sin th_i, as (xx, xz, zz)
};

struct GerstnerSums {
    Expr horizontal, displacement, tx, tz, jacobian;
};

// Wave w's terms added to the sums `which` asks for, in GerstnerSum order.
std::vector<Expr> gerstner_terms(unsigned which, const GerstnerWave& w,
                                 const std::vector<Expr>& s) {
    std::vector<Expr> next;
    size_t k = 0;
    Expr dx = w.direction.x(), dz = w.direction.y();
    Expr horizontal = w.horizontal * w.c; // times D_i
    Expr kw = w.horizontal * w.frequency * w.s;
    if (which & kHorizontal) next.push_back(s[k++] + horizontal * w.direction);
    if (which & kDisplacement)
        next.push_back(s[k++] + vec3(horizontal * dx, w.amplitude * w.s, horizontal * dz));
    if (which & kTangents) {
        // dP/dx = (1,0,0) + sum_i D_i.x e_i and dP/dz = (0,0,1) + sum_i D_i.z e_i with
        // e_i = (-k_i D_i.x, m_i, -k_i D_i.z), m_i = A_i w_i cos th_i.
        Expr m = w.amplitude * w.frequency * w.c;
        Expr e = vec3(-kw * dx, m, -kw * dz);
        next.push_back(s[k++] + dx * e);
        next.push_back(s[k++] + dz * e);
    }
    if (which & kJacobian) {
        Expr kx = kw * dx;
        next.push_back(s[k++] + vec3(kx * dx, kx * dz, (kw * dz) * dz));
    }
    return next;
}

GerstnerSums gerstner_sums(Graph& g, Expr grid_xz, Expr time, Expr footprint, unsigned which) {
    GerstnerSums out;
    // The sums in GerstnerSum order: each one's place in the carried values.
    std::vector<Expr*> slots;
    std::vector<Expr> initial;
    auto add = [&](unsigned bit, Expr* slot, Expr start) {
        if (!(which & bit)) return;
        slots.push_back(slot);
        initial.push_back(start);
    };
    Expr zero3 = constant(g, {0.0, 0.0, 0.0});
    add(kHorizontal, &out.horizontal, zero2(g));
    add(kDisplacement, &out.displacement, zero3);
    add(kTangents, &out.tx, constant(g, {1.0, 0.0, 0.0}));
    add(kTangents, &out.tz, constant(g, {0.0, 0.0, 1.0}));
    add(kJacobian, &out.jacobian, zero3);
    const auto sums =
        sum_over_gerstner_waves(g, grid_xz, time, footprint, initial,
                                [which](const GerstnerWave& w, const std::vector<Expr>& s) {
                                    return gerstner_terms(which, w, s);
                                });
    for (size_t k = 0; k < slots.size(); ++k)
        *slots[k] = sums[k];
    return out;
}

Expr gerstner_normal_from(Graph& g, const GerstnerSums& s) {
    // The tangents are parallel only where a steepness-1 crest folds (dP/dx = 0): keep up.
    return named(safe_normalize(cross(s.tz, s.tx), up(g)), "gerstner_normal");
}

} // namespace

// ---- sum of sines ----

WaveBounds sum_of_sines_bounds(Graph& g, Expr time) {
    return wave_bounds(g, sines_defaults(), time);
}

SurfaceSample sum_of_sines_sample(Graph& g, Expr xz, Expr time, Expr footprint, bool height,
                                  bool slope) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.sum_of_sines");
    std::vector<Expr> initial;
    if (height) initial.push_back(constant(g, 0.0));
    if (slope) initial.push_back(zero2(g));
    const auto sums = sum_over_waves(
        g, sines_defaults(), xz, time, footprint, initial,
        [height, slope](const Wave& w, const std::vector<Expr>& s) {
            std::vector<Expr> next;
            if (height) next.push_back(s[0] + w.faded(w.amplitude) * sin(w.theta));
            // d/dp of a sin(f (d . p) + t phi) = a f cos(...) d.
            if (slope)
                next.push_back(s[height ? 1 : 0] +
                               (w.faded(w.amplitude) * w.frequency * cos(w.theta)) * w.direction);
            return next;
        });
    SurfaceSample out;
    if (height) out.height = named(sums[0], "wave_height");
    if (slope) out.slope = named(sums[height ? 1 : 0], "wave_slope");
    return out;
}

Expr sum_of_sines_height(Graph& g, Expr xz, Expr time, Expr footprint) {
    return sum_of_sines_sample(g, xz, time, footprint, true, false).height;
}

Expr sum_of_sines_slope(Graph& g, Expr xz, Expr time, Expr footprint) {
    return sum_of_sines_sample(g, xz, time, footprint, false, true).slope;
}

Expr sum_of_sines_normal_from(Graph& g, Expr slope) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.sum_of_sines");
    // The y component is 1, so the vector never vanishes: a plain normalize is safe.
    return named(normalize(vec3(-slope.x(), constant(g, 1.0), -slope.y())), "wave_normal");
}

Expr sum_of_sines_normal(Graph& g, Expr xz, Expr time, Expr footprint) {
    return sum_of_sines_normal_from(g, sum_of_sines_slope(g, xz, time, footprint));
}

// ---- Gerstner ----

Expr gerstner_displacement(Graph& g, Expr grid_xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    return named(gerstner_sums(g, grid_xz, time, footprint, kDisplacement).displacement,
                 "gerstner_displacement");
}

Expr gerstner_normal(Graph& g, Expr grid_xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    return gerstner_normal_from(g, gerstner_sums(g, grid_xz, time, footprint, kTangents));
}

GerstnerPoint gerstner_point(Graph& g, Expr grid_xz, Expr time, Expr footprint, bool displacement) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    const unsigned which = kTangents | (displacement ? kDisplacement : 0u);
    const GerstnerSums s = gerstner_sums(g, grid_xz, time, footprint, which);
    return {displacement ? named(s.displacement, "gerstner_displacement") : Expr(),
            gerstner_normal_from(g, s), cross(s.tz, s.tx)};
}

Expr gerstner_normal_gpugems(Graph& g, Expr grid_xz, Expr time, Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    // GPU Gems ch. 1, eq. 12: N = (-sum D.x w A C, 1 - sum Q w A S, -sum D.z w A C). It drops
    // the products between different waves that the exact cross product keeps (exact for one
    // wave); evaluated here at the grid point, like the exact normal, to isolate that error.
    const auto sums = sum_over_gerstner_waves(
        g, grid_xz, time, footprint, {zero2(g), constant(g, 0.0)},
        [](const GerstnerWave& w, const std::vector<Expr>& s) {
            return std::vector<Expr>{s[0] + (w.amplitude * w.frequency * w.c) * w.direction,
                                     s[1] + w.horizontal * w.frequency * w.s};
        });
    Expr xz = sums[0], y = sums[1];
    return named(safe_normalize(vec3(-xz.x(), 1.0 - y, -xz.y()), up(g)), "gerstner_normal_gpugems");
}

Expr gerstner_grid_point(Graph& g, Expr world_xz, Expr time, Expr start, int iterations,
                         Expr footprint) {
    FullPrecisionScope full(g);
    OriginScope scope(g, "waves.gerstner");
    Expr x0 = start;
    for (int i = 0; i < iterations; ++i)
        x0 = named(world_xz - gerstner_sums(g, x0, time, footprint, kHorizontal).horizontal,
                   "gerstner_grid_point");
    return x0;
}

WaveBounds gerstner_bounds(Graph& g, Expr time) {
    return wave_bounds(g, gerstner_defaults(), time);
}

// One Newton step towards the grid point x0 with x0 + horizontal(x0) = world_xz, from x0.
// The Jacobian J = I - sum_i k_i D_i D_i^T (k_i = Q_i A_i w_i sin th_i) is symmetric with
// eigenvalues in [1 - Q, 1 + Q] for unit directions; its determinant is floored (a damped step
// where a steep crest nearly folds) so the step stays finite and continuous in its inputs.
// Same sines and cosines as the displacement and normal at x0: no extra transcendentals.
Expr gerstner_grid_newton(Graph& g, Expr world_xz, Expr time, Expr x0, Expr footprint) {
    const GerstnerSums s = gerstner_sums(g, x0, time, footprint, kHorizontal | kJacobian);
    Expr jxx = 1.0 - s.jacobian.x(), jzz = 1.0 - s.jacobian.z(), jxz = -s.jacobian.y();
    Expr f = named(x0 + s.horizontal - world_xz, "gerstner_grid_residual");
    Expr det = named(max(jxx * jzz - jxz * jxz, 0.04), "gerstner_grid_det");
    Expr step = vec2(jzz * f.x() - jxz * f.y(), jxx * f.y() - jxz * f.x()) / det;
    return named(x0 - step, "gerstner_grid_point");
}

// ---- height map ----

Parameter gerstner_steepness() {
    return {.name = "gerstner_steepness",
            .type = Type::Float,
            .default_value = {0.5},
            .max = 1.0,
            .seed = "004"};
}

Parameter heightmap_scale() {
    return {.name = "heightmap_scale",
            .type = Type::Float,
            .default_value = {0.06},
            .min = 1e-4,
            .max = 100.0,
            .unit = "1/m",
            .seed = "000"};
}

Parameter heightmap_scroll() {
    return {.name = "heightmap_scroll",
            .type = Type::Vec2,
            .default_value = {0.01, -0.02},
            .min = -10.0,
            .max = 10.0,
            .unit = "1/s",
            .seed = "000"};
}

Parameter heightmap_amplitude() {
    return {.name = "heightmap_amplitude",
            .type = Type::Float,
            .default_value = {0.3},
            .max = 10.0,
            .unit = "m",
            .seed = "000"};
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
    Expr scale = uniform(g, heightmap_scale());
    Expr scroll = uniform(g, heightmap_scroll());
    Expr texels = uniform(g, {.name = "heightmap_texels",
                              .type = Type::Float,
                              .default_value = {64.0},
                              .min = 2.0,
                              .max = 16384.0,
                              .unit = "texels",
                              .seed = "000"});
    // With the scene's clock xz is in the frame: the host adds c scale + scroll t mod 1.
    Expr uv = is_scene_clock(time)
                  ? xz * scale + scroll_offset(g, "heightmap_uv_offset", heightmap_scale(),
                                               heightmap_scroll())
                  : xz * scale + time * scroll;
    // Level 0 explicitly: the tile wrap makes implicit derivatives jump at seams, and a
    // vertex stage or a probe has none.
    Expr b = sample_level(texture(g, height_map_texture()), tile_coordinate(uv, texels),
                          constant(g, 0.0))
                 .x();
    if (footprint.valid()) {
        // Without mip levels the map can only fade as a whole: by its highest frequency
        // (heightmap_max_cycles per tile), between 4 and 2 footprints per wavelength as the
        // analytic waves do (sum_over_waves).
        Expr cycles = uniform(g, {.name = "heightmap_max_cycles",
                                  .type = Type::Float,
                                  .default_value = {3.7},
                                  .max = 1e4,
                                  .unit = "1/tile",
                                  .seed = "000"});
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
    Expr d = uniform(g, {.name = "heightmap_normal_offset",
                         .type = Type::Float,
                         .default_value = {0.25},
                         .max = 10.0,
                         .unit = "m",
                         .seed = "000"});
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
    Expr strength = uniform(g, {.name = "heightmap_normal_strength",
                                .type = Type::Float,
                                .default_value = {1.0},
                                .max = 100.0,
                                .seed = "000"});
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
