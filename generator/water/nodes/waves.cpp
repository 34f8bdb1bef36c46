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

// The surface search's steps (see surface_search).
struct Search {
    const Surface& s;
    const SurfaceModel& model;
    Expr pixel_angle, r_safe, ray_down;

    // What a step carries to the next: the level, the bracket [lo, hi] and the model's state.
    struct Carry {
        Expr level, hi, lo, state;
    };
    // The model at a hit: what was asked for of its height and slope, and its state there.
    struct At {
        Expr height, slope, state;
    };

    // Extent of the pixel on the water at distance t, along the view direction where the
    // grazing ray stretches it most (the band limit of the waves, see wave_families.cpp).
    Expr footprint(const PlaneHit& h) const {
        return pixel_angle.valid() ? named(pixel_angle * h.distance / ray_down, "pixel_footprint")
                                   : Expr();
    }

    // Only what a step reads is asked for: a loop computes every sum it carries, read or not.
    At at(const PlaneHit& hit, Expr state, bool height, bool slope) const {
        Expr xz = hit.point.xz(), fp = footprint(hit);
        if (!model.state.advance) {
            const SurfaceSample m = model.sample(xz, fp, height, slope);
            return {m.height, m.slope, state};
        }
        Expr here = model.state.advance(xz, fp, state);
        const SurfaceSample m = model.state.sample_at(xz, fp, here, height, slope);
        return {m.height, m.slope, here};
    }

    // The step from `c` with the model `m` at its level: a safe step (`newton` false), a
    // Newton step (`safe` invalid), or either as the Bool `safe` says.
    Carry step(const Carry& c, const At& m, Expr safe, bool newton) const {
        Graph& g = s.g;
        Expr f = named(s.level + m.height, "search_target") - c.level;
        const Carry safe_step{named(c.level + r_safe * f, "search_level"), c.level, c.lo, m.state};
        if (!newton) return safe_step;
        Expr t_slope = -dot(m.slope, s.view_ray.xz()) / ray_down;
        Expr r =
            named(clamp(1.0 / max(1.0 - t_slope, 1e-6), r_safe, constant(g, 1.0)), "search_step");
        Expr next = named(c.level + r * f, "search_level");
        Expr above = f < 0.0;
        Expr high = named(select(above, c.level, c.hi), "search_high");
        Expr low = named(select(above, c.lo, c.level), "search_low");
        // T' >= 1: Newton would step away from the bracket's crossing (towards one where
        // the ray leaves the surface); the clamped step r = 1 then expands errors by T'
        // per step (measured: float and double apart by 2x per step, 2.6e-4 at the end).
        Expr outside = (next < low) || (next > high) || (t_slope >= 1.0);
        next = named(select(outside, 0.5 * (low + high), next), "search_level");
        if (!safe.valid()) return {next, high, low, m.state};
        return {named(select(safe, safe_step.level, next), "search_level"),
                select(safe, c.level, high), select(safe, c.lo, low), m.state};
    }
};

} // namespace

// One loop for both phases and the final slope (model.one_loop), else a loop per phase.
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
    // |ray.y| guarded as in search_relaxation.
    const Search x{s, model, pixel_angle, search_relaxation(g, s.view_ray, model.max_slope),
                   max(-s.view_ray.y(), 1e-6)};
    Expr level = named(s.level + model.top, "search_level");
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
    // A stateless model carries a constant 0 that nothing reads (the compilers drop it).
    Search::Carry c{level, level, named(s.level - model.top, "search_low"),
                    model.state.start ? model.state.start(intersect_plane(s, level).point.xz())
                                      : constant(g, 0.0)};
    auto carry = [](const std::vector<Expr>& v) { return Search::Carry{v[0], v[1], v[2], v[3]}; };
    if (model.one_loop && steps > safe_steps) {
        // The last iteration only samples the model where the steps ended: its slope.
        const auto r = loop(g, steps + 1, {c.level, c.hi, c.lo, c.state, constant(g, {0.0, 0.0})},
                            [&](Expr i, const std::vector<Expr>& v) {
                                const Search::Carry ci = carry(v);
                                const Search::At m =
                                    x.at(intersect_plane(s, ci.level), ci.state, true, true);
                                const Search::Carry n = x.step(ci, m, i < double(safe_steps), true);
                                Expr level = select(i < double(steps), n.level, ci.level);
                                return LoopStep{{level, n.hi, n.lo, n.state, m.slope}, Expr()};
                            });
        const PlaneHit hit = intersect_plane(s, r[0]);
        return {hit.point, hit.distance, r[4]};
    }
    auto phase = [&](int count, bool newton) {
        if (count <= 0) return;
        const auto r =
            loop(g, count, {c.level, c.hi, c.lo, c.state}, [&](Expr, const std::vector<Expr>& v) {
                const Search::Carry ci = carry(v);
                const Search::At m = x.at(intersect_plane(s, ci.level), ci.state, true, newton);
                const Search::Carry n = x.step(ci, m, Expr(), newton);
                return LoopStep{{n.level, n.hi, n.lo, n.state}, Expr()};
            });
        c = carry(r);
    };
    phase(safe_steps, false);
    phase(steps - safe_steps, true);
    const PlaneHit hit = intersect_plane(s, c.level);
    return {hit.point, hit.distance, x.at(hit, c.state, false, true).slope};
}

SurfaceModel sum_of_sines_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.sum_of_sines");
    auto [top, slope] = sum_of_sines_bounds(g, time);
    SurfaceModel model{top, slope, [&g, time](Expr xz, Expr fp, bool height, bool slope) {
                           return sum_of_sines_sample(g, xz, time, fp, height, slope);
                       }};
    model.one_loop = true;
    return model;
}

SurfaceModel gerstner_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.gerstner");
    auto [top, slope] = gerstner_bounds(g, time);
    Expr steepness = uniform(g, gerstner_steepness());
    // The height above world xz is the height of the grid point x0 with x0 + horizontal(x0)
    // = xz: one Newton step per search step refines x0 (gerstner_grid_newton). A fixed-point
    // step (a contraction by only Q) lagged metres behind when a grazing ray's S moved by
    // half a wavelength, so the search saw heights and slopes of the wrong place.
    // The height is corrected to first order for the step's remaining miss (S minus the
    // displaced x0, up to metres while S still moves) with the world slope at x0, which the
    // Newton steps of the search compute anyway: without that, a height from a stale x0 put
    // the search's bracket on the wrong side of the surface (residuals up to 1.3 cm on rays
    // 20 degrees down). Crests bunch the grid by up to 1 / (1 - Q), which steepens the world
    // slope by as much. Height and slope at the same S share one loop over the waves.
    auto sample_at = [&g, time](Expr xz, Expr fp, Expr x0, bool height, bool slope) {
        const GerstnerPoint p = gerstner_point(g, x0, time, fp, height);
        FullPrecisionScope full(g);
        OriginScope scope(g, "waves.gerstner");
        // dh/dx = -n.x / n.y; n.y > 0 unless a steepness-1 crest folds, where the
        // max() caps the slope instead of dividing by zero.
        Expr world_slope = named(-p.normal.xz() / max(p.normal.y(), 1e-4), "wave_slope");
        SurfaceSample out;
        if (slope) out.slope = world_slope;
        if (height) {
            Expr miss = xz - (x0 + p.displacement.swizzle("xz"));
            out.height = named(p.displacement.y() + dot(world_slope, miss), "gerstner_height");
        }
        return out;
    };
    // The search carries the grid point (SurfaceModel::State); a sample from one Newton step
    // at xz from xz serves callers that ask once.
    auto advance = [&g, time](Expr xz, Expr fp, Expr x0) {
        FullPrecisionScope full(g);
        OriginScope scope(g, "waves.gerstner");
        return gerstner_grid_newton(g, xz, time, x0, fp);
    };
    SurfaceModel model{top, named(slope / max(1.0 - steepness, 0.2), "gerstner_max_slope"),
                       [sample_at, advance](Expr xz, Expr fp, bool height, bool slope) {
                           return sample_at(xz, fp, advance(xz, fp, xz), height, slope);
                       }};
    model.state = {[](Expr xz) { return xz; }, advance, sample_at};
    model.one_loop = true;
    return model;
}

SurfaceModel heightmap_surface(Graph& g, Expr time) {
    OriginScope scope(g, "waves.heightmap_march");
    Expr amplitude = uniform(g, heightmap_amplitude());
    Expr scale = uniform(g, heightmap_scale());
    // A property of the texture: the largest |grad| of its values per tile (the scene's map
    // stays under 2 pi sum |w| |(m, n)| = 17.52, see render/scene_wave_inputs.cpp).
    Expr gradient = uniform(g, {.name = "heightmap_max_gradient",
                                .type = Type::Float,
                                .default_value = {17.6},
                                .max = 1e4,
                                .unit = "1/tile",
                                .seed = "000"});
    return {amplitude, named(amplitude * scale * gradient, "heightmap_max_slope"),
            [&g, time](Expr xz, Expr fp, bool height, bool slope) {
                return SurfaceSample{height ? heightmap_height(g, xz, time, fp) : Expr(),
                                     slope ? heightmap_slope(g, xz, time, fp) : Expr()};
            }};
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

// A mesh fragment (geometry mesh or tessellated): the surface is the rasterised point of the
// displaced grid, and the slope the model's at its grid point, per fragment (not interpolated
// from the vertices), band-limited to the pixel as the screen pass' is.
void compose_mesh_waves(Surface& s, const WaveSearch& search) {
    Graph& g = s.g;
    FullPrecisionScope full(g);
    set_water_column(s, named(length(s.surface_point - s.eye), "surface_distance"));
    if (!search.model) return;
    const SurfaceModel model = search.model(g, s.time);
    Expr footprint = pixel_footprint(s);
    s.wave_slope =
        model.state.sample_at
            ? model.state.sample_at(s.surface_point.xz(), footprint, s.grid_xz, false, true).slope
            : model.sample(s.grid_xz, footprint, false, true).slope;
}

void compose_waves(Surface& s, const std::string& origin, const WaveSearch& search) {
    OriginScope scope(s.g, origin);
    if (s.grid_xz.valid()) {
        compose_mesh_waves(s, search);
        return;
    }
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

} // namespace

void compose_converged_waves(Surface& s, const std::string& choice) {
    const std::string origin = "waves." + choice;
    if (choice == "sum_of_sines")
        compose_waves(
            s, origin,
            {&sum_of_sines_surface, kWaveSurfaceConvergedSteps, kWaveSurfaceConvergedSafeSteps});
    else if (choice == "gerstner")
        compose_waves(
            s, origin,
            {&gerstner_surface, kWaveSurfaceConvergedSteps, kWaveSurfaceConvergedSafeSteps});
    else if (choice == "heightmap_march" || choice == "heightmap_march_converged")
        compose_waves(
            s, origin,
            {&heightmap_surface, kHeightmapMarchConvergedSteps, kHeightmapMarchConvergedSafeSteps});
    else
        compose_choice(s, "waves", choice);
}

namespace {

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
