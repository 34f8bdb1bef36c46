#include "watergen/caustics/caustics_pass.h"

#include "watergen/ir/core/dsl.h"
#include "watergen/water/mesh_shader.h"
#include "watergen/water/nodes/caustics.h"
#include "watergen/water/nodes/fresnel.h"
#include "watergen/water/nodes/waves.h"
#include "watergen/water/scene_quantities.h"

namespace watergen {

namespace {

// One grid point's light, common to both methods.
struct RayToBottom {
    Expr light;       // unit, the way sunlight travels
    Expr clip;        // the landing point in the caustics texture's clip space
    Expr landing;     // where the refracted ray meets the bottom (xz, m)
    Expr to_landing;  // from the grid point to the landing point
    Expr to_beam;     // from the grid point to where the ray crossed the water plane unbent
    Expr area_normal; // dP/dz x dP/dx of the surface at the grid point
};

// The water pass' own definitions of the shared parameters (mesh_shader.h, nodes/fresnel.h):
// one uniform set drives every pass. Heights are taken from the water level and
// the bottom lies caustics_depth below it, so the level itself does not enter.
RayToBottom trace(Graph& g, const std::string& model, Expr grid) {
    Expr time = scene_time(g);
    Expr sun = scene_sun_direction(g);
    Expr ior = uniform(g, ior_water());
    Expr depth = uniform(g, {.name = "caustics_depth",
                             .type = Type::Float,
                             .default_value = {5.0},
                             .max = 1e4,
                             .unit = "m",
                             .seed = "002",
                             .origin = "caustics"});
    Expr window = uniform(g, caustics_window()); // the water pass's caustics axis reads it too
    // The surface point as the grid point moved by `shift` (horizontal) and `height` (above
    // the water level), and its unit normal. Kept as displacements: under flat water they are
    // exactly 0, where differences of positions would carry float rounding.
    RayToBottom r;
    Expr shift, height, normal;
    if (model == "sum_of_sines") {
        const SurfaceSample at = sum_of_sines_sample(g, grid, time, Expr(), true, true);
        shift = constant(g, {0.0, 0.0});
        height = at.height;
        normal = sum_of_sines_normal_from(g, at.slope);
        r.area_normal = vec3(-at.slope.x(), constant(g, 1.0), -at.slope.y());
    } else if (model == "gerstner") {
        const GerstnerPoint at = gerstner_point(g, grid, time, Expr());
        Expr d = at.displacement;
        shift = vec2(d.x(), d.z());
        height = d.y();
        normal = at.normal;
        r.area_normal = at.area_normal;
    } else {
        g.error("caustics: no surface for wave model '" + model + "' (sum_of_sines, gerstner)");
        return r;
    }
    // Sunlight travels down; a sun at or below the horizon lights no bottom, and the guards
    // keep the divisions finite there (the texture is then not meaningful, but not NaN).
    r.light = safe_normalize(sun, constant(g, {0.0, -1.0, 0.0}));
    Expr light_down = min(r.light.y(), -1e-6);
    Expr refracted = named(refract(r.light, normal, 1.0 / ior), "refracted");
    Expr travel = (height + depth) / max(-refracted.y(), 1e-6);
    // From the grid point: to where the ray meets the bottom, and to where it crossed the
    // water plane before the waves bent it (the beam's cross-section: per unit of it, flat
    // water carries the same light to the same area of bottom).
    r.to_landing = shift + vec2(refracted.x(), refracted.z()) * travel;
    r.to_beam = shift - vec2(r.light.x(), r.light.z()) * (height / light_down);
    r.landing = named(grid + r.to_landing, "landing");
    Expr uv = (r.landing - vec2(window.x(), window.y())) / window.z();
    r.clip = vec4(uv.x() * 2.0 - 1.0, uv.y() * 2.0 - 1.0, constant(g, 0.0), constant(g, 1.0));
    return r;
}

void build_area_ratio_vertex(Graph& g, const std::string& model) {
    OriginScope scope(g, "caustics.area_ratio.vertex");
    const RayToBottom r = trace(g, model, varying(g, "grid_xz", Type::Vec2));
    if (!r.clip.valid()) return;
    g.set_output("position", r.clip.id());
    g.set_output("landing", r.landing.id());
    // Passed as an offset from the landing point, not as the beam point itself: under flat
    // water it is exactly constant, so its derivatives are exactly 0 and the ratio exactly 1
    // (beam points a pixel apart differ by ~0.04 m, and in float their difference would carry
    // a relative error of 1e-5).
    g.set_output("offset", (r.to_beam - r.to_landing).id());
    // The clamp reaches the fragment stage as a varying: the runner binds one parameter block
    // for the pipeline, the vertex stage's (as in the mesh path, whose fragment reads none).
    g.set_output("clamp", uniform(g, {.name = "caustics_clamp",
                                      .type = Type::Float,
                                      .default_value = {5.0},
                                      .max = 1e30,
                                      .seed = "HDRP",
                                      .origin = "largest area ratio a fragment adds"})
                              .id());
}

// |a x b| of two 2D vectors: the area of the parallelogram they span.
Expr area(Expr a, Expr b) {
    return abs(a.x() * b.y() - a.y() * b.x());
}

void build_area_ratio_fragment(Graph& g) {
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

void build_photon_vertex(Graph& g, const std::string& model) {
    OriginScope scope(g, "caustics.photon_splat.vertex");
    const RayToBottom r = trace(g, model, varying(g, "grid_xz", Type::Vec2));
    if (!r.clip.valid()) return;
    g.set_output("position", r.clip.id());
    // The photon's light relative to flat water's: the flux a parallel beam pours through its
    // patch of surface over the flux through the same patch of water plane (0 where the
    // surface faces away from the sun, shadowed by the waves in front), times the patch's
    // share of a texel (caustics_photon_share = grid cell area / texel area, set by the host).
    Expr share = uniform(g, {.name = "caustics_photon_share",
                             .type = Type::Float,
                             .default_value = {0.25},
                             .max = 1e6,
                             .seed = "002",
                             .origin = "grid cell area over texel area"});
    Expr flux = max(dot(r.area_normal, -r.light) / -min(r.light.y(), -1e-6), 0.0);
    g.set_output("weight", named(flux * share, "photon_weight").id());
}

void build_photon_fragment(Graph& g) {
    OriginScope scope(g, "caustics.photon_splat.fragment");
    Expr weight = varying(g, "v_weight", Type::Float);
    g.set_output("color", vec4(weight, weight, weight, constant(g, 1.0)).id());
}

} // namespace

const char* caustics_skeleton(CausticsMethod method) {
    return method == CausticsMethod::AreaRatio ? "caustics" : "caustics_photons";
}

std::optional<CausticsMethod> caustics_pass_method(const std::string& caustics_choice) {
    if (caustics_choice == "area_ratio") return CausticsMethod::AreaRatio;
    if (caustics_choice == "photon_splat") return CausticsMethod::PhotonSplat;
    return std::nullopt;
}

const char* to_string(CausticsMethod method) {
    return method == CausticsMethod::AreaRatio ? "area_ratio" : "photon_splat";
}

CausticsPass build_caustics_pass(CausticsMethod method, const std::string& wave_model) {
    CausticsPass p{method, wave_model, Graph{}, Graph{}};
    if (method == CausticsMethod::AreaRatio) {
        build_area_ratio_vertex(p.vertex, wave_model);
        build_area_ratio_fragment(p.fragment);
    } else {
        build_photon_vertex(p.vertex, wave_model);
        build_photon_fragment(p.fragment);
    }
    return p;
}

} // namespace watergen
