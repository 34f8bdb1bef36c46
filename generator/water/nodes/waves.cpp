// The waves axis: where the view ray of the post-process pass meets the moving surface of each
// wave model (the families are in wave_families.cpp), and the axis' choices.
#include "watergen/water/nodes/waves.h"

#include <cstdint>
#include <memory>

#include "axis_tables.h"
#include "watergen/water/surface.h"

namespace watergen {

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

namespace {

// surface_search as two loops, a safe phase and a Newton phase, with the same operations in
// the same order as the unrolled search below, which documents them.
WaveHit surface_search_loops(const Surface& s, const SurfaceModel& model, int steps, int safe_steps,
                             Expr pixel_angle) {
    Graph& g = s.g;
    Expr r_safe = search_relaxation(g, s.view_ray, model.max_slope);
    Expr ray_down = max(-s.view_ray.y(), 1e-6);
    auto footprint = [&](const PlaneHit& h) {
        return pixel_angle.valid() ? named(pixel_angle * h.distance / ray_down, "pixel_footprint")
                                   : Expr();
    };
    auto target_at = [&](const PlaneHit& hit) {
        return named(s.level + model.height(hit.point.xz(), footprint(hit)), "search_target");
    };
    Expr level = named(s.level + model.top, "search_level");
    Expr hi = level, lo = named(s.level - model.top, "search_low");
    if (safe_steps > 0) {
        const auto safe = loop(g, safe_steps, {level, hi}, [&](Expr, const std::vector<Expr>& c) {
            Expr f = target_at(intersect_plane(s, c[0])) - c[0];
            return LoopStep{{named(c[0] + r_safe * f, "search_level"), c[0]}, Expr()};
        });
        level = safe[0];
        hi = safe[1];
    }
    if (steps > safe_steps) {
        const auto newton =
            loop(g, steps - safe_steps, {level, hi, lo}, [&](Expr, const std::vector<Expr>& c) {
                const PlaneHit hit = intersect_plane(s, c[0]);
                Expr target = target_at(hit);
                Expr t_slope =
                    -dot(model.slope(hit.point.xz(), footprint(hit)), s.view_ray.xz()) / ray_down;
                Expr step = 1.0 / max(1.0 - t_slope, 1e-6);
                Expr r = named(clamp(step, r_safe, constant(g, 1.0)), "search_step");
                Expr f = target - c[0];
                Expr next = named(c[0] + r * f, "search_level");
                Expr above = f < 0.0;
                Expr high = named(select(above, c[0], c[1]), "search_high");
                Expr low = named(select(above, c[2], c[0]), "search_low");
                Expr outside = (next < low) || (next > high) || (t_slope >= 1.0);
                next = named(select(outside, 0.5 * (low + high), next), "search_level");
                return LoopStep{{next, high, low}, Expr()};
            });
        level = newton[0];
    }
    const PlaneHit hit = intersect_plane(s, level);
    return {hit.point, hit.distance, model.slope(hit.point.xz(), footprint(hit))};
}

} // namespace

WaveHit surface_search(const Surface& s, const SurfaceModel& model, int steps, int safe_steps,
                       Expr pixel_angle) {
    Graph& g = s.g;
    FullPrecisionScope full(g);
    if (!model.stateful) return surface_search_loops(s, model, steps, safe_steps, pixel_angle);
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

SurfaceModel sum_of_sines_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.sum_of_sines");
    auto [top, slope] = sum_of_sines_bounds(g, time);
    return {top, slope,
            [&g, time](Expr xz, Expr fp) { return sum_of_sines_height(g, xz, time, fp); },
            [&g, time](Expr xz, Expr fp) { return sum_of_sines_slope(g, xz, time, fp); }};
}

SurfaceModel gerstner_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.gerstner");
    auto [top, slope] = gerstner_bounds(g, time);
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
            [grid, world_slope](Expr xz, Expr fp) { return world_slope(grid(xz, fp), fp); }, true};
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

namespace {

// How a choice finds the water along the view ray: a surface search over `model`, or the
// plane where there is none.
struct WaveSearch {
    SurfaceModel (*model)(Graph&, Expr time) = nullptr;
    int steps = 0, safe_steps = 0;
};

WaveHit find_wave_surface(const Surface& s, const std::string& origin, const WaveSearch& search,
                          Expr pixel_angle) {
    Graph& g = s.g;
    FullPrecisionScope full(g);
    OriginScope scope(g, origin);
    if (search.model)
        return surface_search(s, search.model(g, s.time), search.steps, search.safe_steps,
                              pixel_angle);
    const PlaneHit hit = intersect_plane(s, s.level);
    return {hit.point, hit.distance, constant(g, {0.0, 0.0})};
}

void compose_waves(Surface& s, const std::string& origin, const WaveSearch& search) {
    OriginScope scope(s.g, origin);
    if (!search.model) {
        const PlaneHit hit = intersect_plane(s, s.level);
        s.surface_point = hit.point;
        set_water_column(s, hit.distance);
        return;
    }
    const WaveHit hit = find_wave_surface(s, origin, search, pixel_angle(s));
    s.surface_point = hit.point;
    set_water_column(s, hit.distance);
    s.wave_slope = hit.slope;
}

// The catalog node of a choice: where a view ray from `eye` meets the water -> (point, distance).
ChoiceInfo waves_choice(ChoiceInfo info, WaveSearch search, const std::string& reads = "") {
    const std::string origin = "waves." + info.name;
    ChoiceNode node{{{"eye", Type::Vec3},
                     {"view_ray", Type::Vec3},
                     {"level", Type::Float},
                     {"time", Type::Float}},
                    [origin, search](Graph& g, const std::vector<Expr>& in) {
                        FullPrecisionScope full(g); // points 5e6 m away overflow half
                        Surface s(g);
                        s.eye = in[0];
                        s.view_ray = in[1];
                        s.level = in[2];
                        s.time = in[3];
                        const WaveHit hit = find_wave_surface(s, origin, search, Expr());
                        return vec4(hit.point, hit.distance);
                    },
                    "surface point and ray distance (vec4) where the view ray meets the water" +
                        reads};
    return feature_choice(std::move(info), std::move(node),
                          [origin, search](Surface& s) { compose_waves(s, origin, search); });
}

// The families' own nodes at full detail (no footprint): the catalog evaluates points, not pixels.
std::vector<CatalogNode> wave_family_nodes() {
    using Node = Expr (*)(Graph&, Expr, Expr, Expr);
    auto node = [](const std::string& name, const std::string& what, Node f,
                   const std::string& approximates = "") {
        return CatalogNode{
            name,
            what,
            {{"xz", Type::Vec2}, {"time", Type::Float}},
            [f](Graph& g, const std::vector<Expr>& in) { return f(g, in[0], in[1], Expr()); },
            approximates};
    };
    const Node heightmap = [](Graph& g, Expr xz, Expr time, Expr) {
        return heightmap_height(g, xz, time);
    };
    return {
        node("waves.sum_of_sines.height", "height above the water level at xz, m",
             &sum_of_sines_height),
        node("waves.sum_of_sines.slope", "(dh/dx, dh/dz) at xz", &sum_of_sines_slope),
        node("waves.sum_of_sines.normal", "unit normal at xz", &sum_of_sines_normal),
        node("waves.gerstner.displacement", "displacement of grid point xz, m",
             &gerstner_displacement),
        node("waves.gerstner.normal", "exact unit normal at grid point xz", &gerstner_normal),
        // Exact for one wave; drops the cross terms between waves (water-models.md, "Waves and
        // normals").
        node("waves.gerstner.normal_gpugems", "GPU Gems' closed-form normal at grid point xz",
             &gerstner_normal_gpugems, "waves.gerstner.normal"),
        node("waves.heightmap.height", "height-map height at xz, m; reads texture height_map",
             heightmap),
    };
}

} // namespace

AxisInfo waves_axis() {
    const std::string reads_height_map = "; reads texture height_map";
    // 000's march with few iterations approximates the same march run to convergence, the gold
    // (waves_golden_test measures the gap).
    return {"waves",
            "flat",
            {
                waves_choice({.name = "flat", .description = "the water plane"}, {}),
                waves_choice(
                    {.name = "sum_of_sines",
                     .seed = "004",
                     .description = "sum of sines, frequency x1.18 and amplitude x0.82 per wave"},
                    {&sum_of_sines_surface, kWaveSurfaceSteps, kWaveSurfaceSafeSteps}),
                waves_choice({.name = "gerstner", .seed = "004", .description = "Gerstner waves"},
                             {&gerstner_surface, kWaveSurfaceSteps, kWaveSurfaceSafeSteps}),
                waves_choice({.name = "heightmap_march",
                              .seed = "000",
                              .description = "height-map march, 4 iterations",
                              .approximates = "heightmap_march_converged"},
                             {&heightmap_surface, kHeightmapMarchSteps, kHeightmapMarchSafeSteps},
                             reads_height_map),
                waves_choice({.name = "heightmap_march_converged",
                              .seed = "000",
                              .description = "height-map march, 32 iterations",
                              .gold = true},
                             {&heightmap_surface, kHeightmapMarchConvergedSteps,
                              kHeightmapMarchConvergedSafeSteps},
                             reads_height_map),
            },
            wave_family_nodes()};
}

} // namespace watergen
