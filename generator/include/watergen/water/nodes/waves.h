// waves: the families (water/nodes/wave_families.cpp) and where the view ray meets them
// (water/nodes/waves.cpp).
//
// Every function here is geometry: it runs at 32-bit precision even inside a relaxed scope
// (a probe's half mode), because half holds neither 1e5 m nor a day of seconds.
#pragma once

#include <functional>
#include <string>

#include "watergen/ir/core/dsl.h"

namespace watergen {

struct Surface;

// Waves per model: data, parameter <family>_wave_count (004 sums "numberOfWaves" sines), the
// trip count of a loop over the waves of at most kMaxWaves. Four by default: enough to break up
// the pattern over the synthetic scene.
constexpr int kMaxWaves = 8;
constexpr int kDefaultWaveCount = 4;
// Post-process surface search for sum_of_sines / gerstner (see surface_search): steps along
// the view ray, each one height and slope evaluation (a loop over the waves; Gerstner adds
// the grid step and its normal), the first kWaveSurfaceSafeSteps Lipschitz-safe, the rest
// Newton steps. Measured over the synthetic scene in waves_golden_test.
constexpr int kWaveSurfaceSteps = 8;
constexpr int kWaveSurfaceSafeSteps = 1;
// 000's height-map march: the axis choices heightmap_march (Lipschitz-safe steps only, one
// sample each) and heightmap_march_converged (the gold: Newton steps with central-difference
// slopes, five samples each).
constexpr int kHeightmapMarchSteps = 4;
constexpr int kHeightmapMarchSafeSteps = kHeightmapMarchSteps;
constexpr int kHeightmapMarchConvergedSteps = 32;
constexpr int kHeightmapMarchConvergedSafeSteps = 4;
// The same searches run to convergence, for references (compose_converged_waves): the bracket
// halves at least every other step, so 64 steps leave it far below a float ulp of any height.
constexpr int kWaveSurfaceConvergedSteps = 64;
constexpr int kWaveSurfaceConvergedSafeSteps = 4;

// The waves axis' `choice` composed as a reference: its surface search run for
// kWaveSurfaceConvergedSteps (the screen pass' 8 steps leave grazing rays short of the
// crossing, waves_golden_test), so a mesh's geometric error is measured against the surface
// itself. A choice without a search composes as it is.
void compose_converged_waves(Surface& s, const std::string& choice);

// v / |v|, or `fallback` when |v|^2 <= 1e-30 or is NaN (normalize of a zero vector is NaN on
// the CPU and undefined on GPUs). Never produces a NaN itself.
Expr safe_normalize(Expr v, Expr fallback);
// The same for vectors of any finite length (1e-30 to 1e30): divided by its largest component
// first, so |v|^2 cannot overflow or underflow in float. For inputs not known to be unit.
Expr robust_normalize(Expr v, Expr fallback);

// Band limit: `footprint` (m), when given, is a pixel's extent on the water; each wave then
// fades out as its wavelength drops from 4 to 2 footprints (beyond that it is aliasing noise
// in the pixel). Without it (points: probes, the mesh path) every wave is in full.

// Bounds of a family at its parameters: no crest is higher than `top` above the water level
// (sum of a_i, m) and no |grad h| exceeds `max_slope` (sum of a_i f_i).
struct WaveBounds {
    Expr top;
    Expr max_slope;
};

// A wave model at one point: the height above the water level (m) and (dh/dx, dh/dz); either is
// invalid when not asked for.
struct SurfaceSample {
    Expr height;
    Expr slope;
};

// Each family sums its waves in one loop (of <family>_wave_count iterations, at most kMaxWaves)
// per point; the functions below that return several values at a point share that loop.
// Parameters per family: <family>_amplitude A (m), <family>_frequency F (rad/m),
// <family>_amplitude_gain, <family>_frequency_gain (a_i = A gain^i, f_i = F gain^i),
// <family>_wave_count (0..8, default 4), <family>_wave_directions (vec2[8], d_i, unit xz) and
// <family>_wave_speeds (float[8], phi_i, rad/s).

// ---- sum of sines (004), family "waves" ----
// h(p) = sum_i a_i sin(f_i (d_i . p) + t phi_i), a_i = A 0.82^i, f_i = F 1.18^i.
Expr sum_of_sines_height(Graph& g, Expr xz, Expr time, Expr footprint = Expr()); // m
Expr sum_of_sines_slope(Graph& g, Expr xz, Expr time, Expr footprint = Expr());  // dh/dx, dh/dz
Expr sum_of_sines_normal(Graph& g, Expr xz, Expr time, Expr footprint = Expr()); // unit
// The height and / or the slope from one loop.
SurfaceSample sum_of_sines_sample(Graph& g, Expr xz, Expr time, Expr footprint, bool height,
                                  bool slope);
// The unit normal of a slope (dh/dx, dh/dz).
Expr sum_of_sines_normal_from(Graph& g, Expr slope);
WaveBounds sum_of_sines_bounds(Graph& g, Expr time);

// ---- Gerstner (004, GPU Gems ch. 1), family "gerstner" ----
// A grid point x0 moves to P = (x0.x + sum Q_i A_i D_i.x cos th_i, level + sum A_i sin th_i,
// x0.z + sum Q_i A_i D_i.z cos th_i), th_i = w_i (D_i . x0) + phi_i t, Q_i = Q / (w_i A_i n),
// n the number of waves. Also gerstner_steepness Q in [0, 1].
// P - (x0.x, level, x0.z), m
Expr gerstner_displacement(Graph& g, Expr grid_xz, Expr time, Expr footprint = Expr());
// Exact: normalize(dP/dz x dP/dx).
Expr gerstner_normal(Graph& g, Expr grid_xz, Expr time, Expr footprint = Expr());
// Both from one loop (the displacement only when asked for).
struct GerstnerPoint {
    Expr displacement;
    Expr normal;
    Expr area_normal; // dP/dz x dP/dx: the normal scaled by the surface area per grid area
};
GerstnerPoint gerstner_point(Graph& g, Expr grid_xz, Expr time, Expr footprint,
                             bool displacement = true);
// GPU Gems' closed form (eq. 12), unit.
Expr gerstner_normal_gpugems(Graph& g, Expr grid_xz, Expr time, Expr footprint = Expr());
// Grid point x0 whose displaced position lies above world_xz: `iterations` fixed-point steps
// x0 = world_xz - horizontal(x0) (a contraction for Q < 1), starting from `start`.
Expr gerstner_grid_point(Graph& g, Expr world_xz, Expr time, Expr start, int iterations,
                         Expr footprint = Expr());
WaveBounds gerstner_bounds(Graph& g, Expr time);
// One Newton step from x0 towards the grid point whose displaced position lies above world_xz
// (2x2 Jacobian of the horizontal displacement, determinant floored at 0.04).
Expr gerstner_grid_newton(Graph& g, Expr world_xz, Expr time, Expr x0, Expr footprint);

// ---- height map (000) ----
// Texture "height_map": r = height in [-1, 1], a periodic tile whose texel k sits at tile
// coordinate k / (n - 1), so texel 0 equals texel n - 1 (see render/scene_wave_inputs.cpp).
TextureInput height_map_texture();
// heightmap_amplitude H (m) x the height map at xz * heightmap_scale + time * heightmap_scroll.
// With a footprint (band limit, as above) the map fades as a whole by its highest frequency,
// heightmap_max_cycles per tile (the surface search uses that; the normals do not).
Expr heightmap_height(Graph& g, Expr xz, Expr time, Expr footprint = Expr());
// Central differences of heightmap_height, offset heightmap_normal_offset d (m) and strength
// heightmap_normal_strength s (000): normalize((h(x-d) - h(x+d)) s, 2d, (h(z-d) - h(z+d)) s).
// With `footprint` (m, a pixel's extent on the water) the map fades out as the march's does
// (heightmap_height): a far pixel covers many texels, and its differences would be aliasing
// noise, ill-conditioned besides (float rounding of a 1 km position moved them by 1e-4).
Expr heightmap_normal(Graph& g, Expr xz, Expr time, Expr footprint = Expr());
// (dh/dx, dh/dz) from the same differences.
Expr heightmap_slope(Graph& g, Expr xz, Expr time, Expr footprint = Expr());
// Texture coordinate of a periodic tile with `texels` texels per side for the clamp-to-edge
// sampler: tile coordinate fract(uv) maps onto texel centres 0 .. n - 1.
Expr tile_coordinate(Expr uv, Expr texels);

Parameter heightmap_amplitude(); // H, m: the height map's [-1, 1] scaled
Parameter gerstner_steepness();  // Q of GPU Gems' Gerstner waves, 0 (sines) to 1 (sharp crests)
Parameter heightmap_scale();     // 1/m: tiles a metre, the map's uv = xz * scale
Parameter heightmap_scroll();    // 1/s: the uv the map scrolls per second

// ---- where the view ray meets the water (post-process pass) ----
struct WaveHit {
    Expr point;    // vec3, m
    Expr distance; // float, along the view ray, m
    Expr slope;    // vec2 (dh/dx, dh/dz) at point
};

// A wave model as the surface search sees it: heights above the water level at world xz.
struct SurfaceModel {
    Expr top;       // no crest is higher above the water level, m
    Expr max_slope; // no |grad h| is larger (world units)
    // (world xz, footprint or invalid, height?, slope?) -> what was asked, from one evaluation
    std::function<SurfaceSample(Expr, Expr, bool, bool)> sample;
    // The slope comes with the height at little cost (one loop over the waves sums both): the
    // search then runs its safe steps, Newton steps and final slope as one loop.
    bool one_loop = false;
    // A model that carries a value from one search step to the next (gerstner: the grid point
    // under the searched xz) says so here; the search then keeps it as a loop-carried value.
    // start(first xz) -> state; advance(xz, footprint, state) -> the state at xz, which
    // sample_at(xz, footprint, state, height?, slope?) reads. Empty for stateless models.
    struct State {
        std::function<Expr(Expr)> start;
        std::function<Expr(Expr, Expr, Expr)> advance;
        std::function<SurfaceSample(Expr, Expr, Expr, bool, bool)> sample_at;
    } state{};
};
SurfaceModel sum_of_sines_surface(Graph& g, Expr time);
// Stateful: the search carries the grid point, refined by one Newton step (2x2 Jacobian of the
// horizontal displacement, determinant floored at 0.04) per new world xz; the height is
// corrected to first order (world slope at x0) for what that step leaves of the miss.
SurfaceModel gerstner_surface(Graph& g, Expr time);
SurfaceModel heightmap_surface(Graph& g, Expr time);

// r = 1 / (1 + K |ray.xz| / max(-ray.y, 1e-6)), the damping of surface_search.
Expr search_relaxation(Graph& g, Expr view_ray, Expr max_slope);

// 000's march, generalised to every wave model: start at level = water_level + top, then
// `steps` x { T = water_level + height(S.xz); level += r (T - level); S = the view ray meets
// level } (r = 1 is 000's "level = level + B H"). The first `safe_steps` use r = 1 / (1 + G),
// which keeps every step monotone so the levels descend towards the first crossing of the ray
// with the surface; later steps are Newton steps (from the model's slope) kept within [that r, 1]
// and within a bracket [lo, hi] of the crossing (hi: the last level above the surface, lo: the
// last below it, at first water_level - top); a Newton step leaving the bracket bisects it
// instead (so does a step where T' >= 1, where Newton points away from the crossing), so a
// grazing ray cannot end in a crest-trough cycle whose end float rounding picks.
// The plane intersections go through intersect_plane. Reads s.eye, s.view_ray, s.level.
// `pixel_angle` (radians per pixel, optional) band-limits the model at each step's footprint.
// Loops: with model.one_loop one of steps + 1 iterations (safe and Newton steps picked per
// iteration, the last one only samples the slope where the steps ended), else one per phase
// and the final slope after them; the values are the same either way.
WaveHit surface_search(const Surface& s, const SurfaceModel& model, int steps, int safe_steps,
                       Expr pixel_angle = Expr());

} // namespace watergen
