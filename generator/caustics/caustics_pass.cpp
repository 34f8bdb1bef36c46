#include "watergen/caustics/caustics_pass.h"

#include "watergen/ir/dsl.h"
#include "watergen/water/nodes/waves.h"
#include "watergen/water/scene_quantities.h"

namespace watergen {

namespace {

void build_vertex(Graph& g, const std::string& model) {
    OriginScope scope(g, "caustics.area_ratio.vertex");
    Expr grid = varying(g, "grid_xz", Type::Vec2);
    // The water pass's names and defaults (water_shader.cpp, fresnel.cpp): one uniform set
    // drives both passes.
    // Heights are taken from the water level and the bottom lies caustics_depth below it, so
    // the level itself does not enter.
    Expr time = bind(scene_quantity::time,
                     uniform(g, {"time", Type::Float, {0.0}, 0.0, 86400.0, "s", "000", ""}));
    Expr sun = bind(
        scene_quantity::sun_direction,
        uniform(g, {"sun_direction", Type::Vec3, {-0.35, -0.75, 0.55}, -1.0, 1.0, "", "000", ""}));
    Expr ior = uniform(g, {"ior_water", Type::Float, {1.33333}, 1.0, 3.0, "", "000", ""});
    Expr depth =
        uniform(g, {"caustics_depth", Type::Float, {5.0}, 0.0, 1e4, "m", "002", "caustics"});
    Expr window = uniform(
        g, {"caustics_window", Type::Vec3, {-5.0, -5.0, 10.0}, -1e5, 1e5, "m", "002", "caustics"});
    // The surface point as the grid point moved by `shift` (horizontal) and `height` (above
    // the water level), and its unit normal. Kept as displacements: under flat water they are
    // exactly 0, where differences of positions would carry float rounding.
    Expr shift, height, normal;
    if (model == "sum_of_sines") {
        const SurfaceSample at = sum_of_sines_sample(g, grid, time, Expr(), true, true);
        shift = constant(g, {0.0, 0.0});
        height = at.height;
        normal = sum_of_sines_normal_from(g, at.slope);
    } else if (model == "gerstner") {
        const GerstnerPoint at = gerstner_point(g, grid, time, Expr());
        Expr d = at.displacement;
        shift = vec2(d.x(), d.z());
        height = d.y();
        normal = at.normal;
    } else {
        g.error("caustics: no surface for wave model '" + model + "' (sum_of_sines, gerstner)");
        return;
    }
    // Sunlight travels down; a sun at or below the horizon lights no bottom, and the guards
    // keep the divisions finite there (the texture is then not meaningful, but not NaN).
    Expr light = safe_normalize(sun, constant(g, {0.0, -1.0, 0.0}));
    Expr light_down = min(light.y(), -1e-6);
    Expr refracted = named(refract(light, normal, 1.0 / ior), "refracted");
    Expr travel = (height + depth) / max(-refracted.y(), 1e-6);
    // From the grid point: to where the ray meets the bottom, and to where it crossed the
    // water plane before the waves bent it (the beam's cross-section: per unit of it, flat
    // water carries the same light to the same area of bottom).
    Expr to_landing = shift + vec2(refracted.x(), refracted.z()) * travel;
    Expr to_beam = shift - vec2(light.x(), light.z()) * (height / light_down);
    Expr landing = named(grid + to_landing, "landing");
    Expr size = window.z();
    Expr uv = (landing - vec2(window.x(), window.y())) / size;
    Expr clip = vec4(uv.x() * 2.0 - 1.0, uv.y() * 2.0 - 1.0, constant(g, 0.0), constant(g, 1.0));
    g.set_output("position", clip.id());
    g.set_output("landing", landing.id());
    // Passed as an offset from the landing point, not as the beam point itself: under flat
    // water it is exactly constant, so its derivatives are exactly 0 and the ratio exactly 1
    // (beam points a pixel apart differ by ~0.04 m, and in float their difference would carry
    // a relative error of 1e-5).
    g.set_output("offset", (to_beam - to_landing).id());
    // The clamp reaches the fragment stage as a varying: the runner binds one parameter block
    // for the pipeline, the vertex stage's (as in the mesh path, whose fragment reads none).
    g.set_output("clamp", uniform(g, {"caustics_clamp",
                                      Type::Float,
                                      {5.0},
                                      0.0,
                                      1e30,
                                      "",
                                      "HDRP",
                                      "largest area ratio a fragment adds"})
                              .id());
}

// |a x b| of two 2D vectors: the area of the parallelogram they span.
Expr area(Expr a, Expr b) {
    return abs(a.x() * b.y() - a.y() * b.x());
}

void build_fragment(Graph& g) {
    OriginScope scope(g, "caustics.area_ratio.fragment");
    Expr landing = varying(g, "v_landing", Type::Vec2);
    Expr offset = varying(g, "v_offset", Type::Vec2);
    Expr clamp_at = varying(g, "v_clamp", Type::Float);
    Expr dx = ddx(landing), dy = ddy(landing);
    Expr new_area = area(dx, dy);
    Expr old_area = area(dx + ddx(offset), dy + ddy(offset));
    // new_area is a pixel's area on the bottom (the landing point is the pixel's position):
    // never 0 where the grid folds, but guard it anyway.
    Expr ratio = named(min(old_area / max(new_area, 1e-30), clamp_at), "area_ratio");
    g.set_output("color", vec4(ratio, ratio, ratio, constant(g, 1.0)).id());
}

} // namespace

CausticsPass build_caustics_pass(const std::string& wave_model) {
    CausticsPass p{wave_model, Graph{}, Graph{}};
    build_vertex(p.vertex, wave_model);
    build_fragment(p.fragment);
    return p;
}

} // namespace watergen
