#include "watergen/water/nodes/refraction.h"

#include "axis_tables.h"
#include "watergen/water/nodes/fresnel.h"
#include "watergen/water/nodes/reflection.h"
#include "watergen/water/nodes/waves.h"
#include "watergen/water/surface.h"
#include "watergen/water/water_shader.h"

namespace watergen {

Expr screen_distort_uv(Graph& g, Expr uv, Expr normal, Expr depth) {
    OriginScope scope(g, "refraction.screen_distort");
    // Screen-space offset per unit of horizontal normal; artistic in both seeds.
    Expr strength = uniform(g, {.name = "refraction_distortion",
                                .type = Type::Float,
                                .default_value = {0.03},
                                .max = 1.0,
                                .seed = "003"});
    Expr fade_depth = uniform(g, {.name = "refraction_shore_fade_depth",
                                  .type = Type::Float,
                                  .default_value = {1.0},
                                  .max = 100.0,
                                  .unit = "m",
                                  .seed = "000"});
    // A negative depth (scene a hair above the plane) gives no displacement. A fade depth of
    // 0 turns the fade off; dividing by it would give 0 / 0 at the shoreline, and clamp(NaN)
    // is undefined on GPUs.
    Expr fade =
        named(select(fade_depth > constant(g, 0.0), saturate(depth / fade_depth), constant(g, 1.0)),
              "distortion_fade");
    return named(saturate(uv + normal.xz() * (strength * fade)), "refraction_uv");
}

namespace {

// 002: R = refract(-V, N, n1 / n2); exactly 0 under total internal reflection, unit otherwise.
// refract() assumes unit vectors; its dot(N, I)^2 overflows float on the GPU for vectors of
// length ~1e19 (-nan / -inf there, finite on the CPU), so both are normalised first whatever
// their length (a few instructions, for refracted_ray variants only).
Expr refracted_direction(Graph& g, Expr view_ray, Expr normal) {
    OriginScope scope(g, "refraction.refracted_ray");
    Expr v = robust_normalize(view_ray, constant(g, {0.0, -1.0, 0.0}));
    Expr n = robust_normalize(normal, constant(g, {0.0, 1.0, 0.0}));
    return named(refract(v, n, uniform(g, ior_air()) / uniform(g, ior_water())), "refracted_ray");
}

} // namespace

Expr refracted_ray_point(Graph& g, Expr surface_point, Expr view_ray, Expr normal, Expr depth) {
    Expr r = refracted_direction(g, view_ray, normal);
    OriginScope scope(g, "refraction.refracted_ray");
    // 002: clamp(dv, 0.0, 2.0) / 3.0.
    Expr dv_max = uniform(g, {.name = "refraction_dv_max",
                              .type = Type::Float,
                              .default_value = {2.0},
                              .max = 100.0,
                              .unit = "m",
                              .seed = "002"});
    Expr dv_scale = uniform(g, {.name = "refraction_dv_scale",
                                .type = Type::Float,
                                .default_value = {1.0 / 3.0},
                                .max = 10.0,
                                .seed = "002"});
    FullPrecisionScope geometry(g);
    // clamp(+inf, 0, max) = max: a bottomless pixel still lands a bounded step away.
    Expr dv = named(clamp(depth, constant(g, 0.0), dv_max) * dv_scale, "refraction_dv");
    return named(surface_point + r * dv, "refracted_point");
}

Expr refracted_ray_uv(Graph& g, Expr uv, Expr surface_point, Expr view_ray, Expr normal,
                      Expr depth) {
    Expr w_point = refracted_ray_point(g, surface_point, view_ray, normal, depth);
    Expr r = refracted_direction(g, view_ray, normal); // the same node as inside W
    OriginScope scope(g, "refraction.refracted_ray");
    Expr transmitted = named(dot(r, r) > constant(g, 0.5), "transmitted");
    const ProjectiveUv p = projective_uv(g, w_point, "refraction", "002", constant(g, 1.0));
    return named(select(transmitted && p.valid, p.uv, uv), "refraction_uv");
}

namespace {

Expr scene_color_at(Graph& g, Expr uv) {
    return sample(texture(g, scene_color_texture()), uv).xyz();
}

// The refracted colour: the scene colour at `uv`.
void compose_refraction(Surface& s, const std::string& origin, Expr uv) {
    OriginScope scope(s.g, origin);
    s.refracted = named(scene_color_at(s.g, uv), "refracted");
}

std::vector<CatalogNode> refraction_nodes() {
    return {
        {"refraction.screen_distort_uv",
         "000/003 uv + N.xz strength, faded towards the shore",
         {{"uv", Type::Vec2}, {"normal", Type::Vec3}, {"depth", Type::Float}},
         [](Graph& g, const std::vector<Expr>& in) {
             return screen_distort_uv(g, in[0], in[1], in[2]);
         }},
        {"refraction.refracted_ray_point",
         "002 W = U + dv refract(-V, N, n1/n2), dv clamped",
         {{"surface_point", Type::Vec3},
          {"view_ray", Type::Vec3},
          {"normal", Type::Vec3},
          {"depth", Type::Float}},
         [](Graph& g, const std::vector<Expr>& in) {
             return refracted_ray_point(g, in[0], in[1], in[2], in[3]);
         }},
        {"refraction.refracted_ray_uv",
         "002 screen uv of W; the pixel's uv under TIR or behind the camera",
         {{"uv", Type::Vec2},
          {"surface_point", Type::Vec3},
          {"view_ray", Type::Vec3},
          {"normal", Type::Vec3},
          {"depth", Type::Float}},
         [](Graph& g, const std::vector<Expr>& in) {
             return refracted_ray_uv(g, in[0], in[1], in[2], in[3], in[4]);
         }},
    };
}

} // namespace

AxisInfo refraction_axis() {
    return {"refraction",
            "screen_distort",
            {
                {.name = "none",
                 .description = "scene colour at the pixel",
                 .compose =
                     [](Surface& s) {
                         OriginScope scope(s.g, "refraction.none");
                         s.refracted = s.scene_rgb;
                     }},
                {.name = "screen_distort",
                 .seed = "000",
                 .description = "scene colour at uv displaced by the normal",
                 .compose =
                     [](Surface& s) {
                         compose_refraction(s, "refraction.screen_distort",
                                            screen_distort_uv(s.g, s.uv, s.normal, s.depth));
                     }},
                {.name = "refracted_ray",
                 .seed = "002",
                 .description = "scene colour where the refracted ray W = U + dv R meets the bed",
                 .compose =
                     [](Surface& s) {
                         compose_refraction(s, "refraction.refracted_ray",
                                            refracted_ray_uv(s.g, s.uv, s.surface_point, s.view_ray,
                                                             s.normal, s.depth));
                     }},
            },
            refraction_nodes()};
}

} // namespace watergen
