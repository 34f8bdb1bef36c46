#include "watergen/water/nodes/reflection.h"

#include "axis_tables.h"
#include "watergen/water/nodes/waves.h"
#include "watergen/water/surface.h"

namespace watergen {

Parameter sky_color() {
    return {.name = "sky_color",
            .type = Type::Vec3,
            .default_value = {0.55, 0.7, 0.9},
            .max = 1e3,
            .seed = "000"};
}

TextureInput sky_cube_texture() {
    return {"sky_cube", Type::TextureCube,
            "environment cube map around the water, linear rgb (001)", ""};
}

TextureInput reflection_map_texture() {
    return {"reflection_map", Type::Texture2D,
            "scene above the water seen from the eye mirrored in the water plane, field of view x "
            "reflection_fov_extension, "
            "linear rgb (001, 002)",
            ""};
}

TextureInput fourier_coefs1_texture() {
    return {"fourier_coefs1", Type::Texture2D,
            "horizon Fourier coefficients a0, a1, b1, a2 over the water plane (003)", ""};
}

TextureInput fourier_coefs2_texture() {
    return {"fourier_coefs2", Type::Texture2D,
            "horizon Fourier coefficients b2, a3, b3, a4 over the water plane (003)", ""};
}

Parameter reflection_fov_extension() {
    return {.name = "reflection_fov_extension",
            .type = Type::Float,
            .default_value = {1.5},
            .min = 1.0,
            .max = 4.0,
            .seed = "002"};
}

Parameter fourier_map_origin() {
    return {.name = "fourier_map_origin",
            .type = Type::Vec2,
            .default_value = {-40.0, -10.0},
            .min = -1e7,
            .max = 1e7,
            .unit = "m",
            .seed = "003",
            .host = {HostRule::FramePointXZ, {}}};
}

Parameter fourier_map_size() {
    return {.name = "fourier_map_size",
            .type = Type::Vec2,
            .default_value = {80.0, 80.0},
            .min = 1e-3,
            .max = 1e6,
            .unit = "m",
            .seed = "003"};
}

namespace {

Parameter view_proj_column(const std::string& prefix, int k, const std::string& seed) {
    // Identity until the engine sets the camera: finite lookups, never NaN.
    std::vector<double> column(4, 0.0);
    column[static_cast<size_t>(k)] = 1.0;
    // The engine's world-to-clip matrix; the host moves its translation into the frame.
    const std::string name = prefix + "_view_proj_c";
    HostValue host;
    if (k == 3) host = {HostRule::FrameWorldToClip, {name + "0", name + "2"}};
    return {.name = name + std::to_string(k),
            .type = Type::Vec4,
            .default_value = column,
            .min = -1e6,
            .max = 1e6,
            .seed = seed,
            .host = host};
}

// A unit-length horizontal direction (x, z) of `v`, or (1, 0) when v is vertical: the seed's
// normalize(float2) of a zero vector is NaN. The threshold is a normal float and rounds to 0 in
// binary16, where the compared length has already rounded to 0 too.
Expr horizontal_direction(Graph& g, Expr v) {
    Expr xz = v.xz();
    Expr len2 = named(dot(xz, xz), "horizontal_length2");
    return named(select(len2 > constant(g, 1e-12), xz * rsqrt(len2), constant(g, {1.0, 0.0})),
                 "azimuth");
}

} // namespace

ProjectiveUv projective_uv(Graph& g, Expr point, const std::string& prefix, const std::string& seed,
                           Expr fov_scale) {
    FullPrecisionScope geometry(g);
    Expr c0 = uniform(g, view_proj_column(prefix, 0, seed));
    Expr c1 = uniform(g, view_proj_column(prefix, 1, seed));
    Expr c2 = uniform(g, view_proj_column(prefix, 2, seed));
    Expr c3 = uniform(g, view_proj_column(prefix, 3, seed));
    Expr q = named(c0 * point.x() + c1 * point.y() + c2 * point.z() + c3, prefix + "_clip");
    Expr w = q.w();
    // 001's projective divide is undefined on the camera plane (x / 0, 0 / 0) and mirrors
    // points behind it back onto the texture: those get the texture centre, so no NaN or
    // mirrored coordinate reaches a sampler, and `valid` says the lookup means nothing.
    Expr valid = named(w > constant(g, kMinProjectiveW), prefix + "_in_front");
    // fov_scale >= 1 by its range; the max keeps a zero from dividing.
    Expr uv = saturate(0.5 * (q.xy() / w) / max(fov_scale, 1.0) + 0.5);
    return {named(select(valid, uv, constant(g, {0.5, 0.5})), prefix + "_uv"), valid};
}

Expr sky_cube_lookup(Graph& g, Expr view_ray, Expr normal) {
    OriginScope scope(g, "reflection.sky_cubemap");
    // 001 blurs the seam between the sky and the tinted mirror image: a band of 0.2 in -R.y
    // (about 12 degrees) stands in for the blur and keeps the colour's slope in R.y small.
    Expr band = uniform(g, {.name = "reflection_horizon_band",
                            .type = Type::Float,
                            .default_value = {0.2},
                            .min = 1e-3,
                            .max = 1.0,
                            .seed = "001"});
    // reflect() needs a unit normal, and the mirrored direction's y is compared with the band
    // as a unit ray's would be. Both are normalised scale-first (robust_normalize, waves.h):
    // dot(N, I) overflows once |N| |I| passes 65504 in 16-bit arithmetic (a view ray of length
    // 1e4 and a normal of length 100 gave inf) and 3.4e38 in 32 bits.
    Expr v = robust_normalize(view_ray, constant(g, {0.0, -1.0, 0.0}));
    Expr n = robust_normalize(normal, constant(g, {0.0, 1.0, 0.0}));
    Expr r = named(reflect(v, n), "reflected_ray");
    // 001: the lower half of the cube would show the water itself, which a cube cannot hold;
    // mirror it into the upper half so every lookup finds sky.
    Expr mirrored = vec3(r.x(), abs(r.y()), r.z());
    Expr dir = named(select(dot(r, r) > constant(g, 1e-12), mirrored, constant(g, {0.0, 1.0, 0.0})),
                     "sky_direction");
    // The band is >= 1e-3 by its range; at 0 smoothstep would divide 0 by 0.
    Expr below = named(smoothstep(constant(g, 0.0), max(band, 1e-3), -r.y()), "below_horizon");
    return vec4(dir, below);
}

Expr planar_reflection_uv(Graph& g, Expr surface_point, Expr normal) {
    OriginScope scope(g, "reflection.planar_projective");
    // 001: d = 4 ("no specific physical meaning"); the xz displacement of the point by the
    // normal stands in for the distortion of a moving surface.
    Expr d = uniform(g, {.name = "reflection_distortion",
                         .type = Type::Float,
                         .default_value = {4.0},
                         .max = 100.0,
                         .unit = "m",
                         .seed = "001"});
    Expr fov = uniform(g, reflection_fov_extension());
    Expr displaced;
    {
        FullPrecisionScope geometry(g);
        displaced = named(surface_point + d * vec3(normal.x(), constant(g, 0.0), normal.z()),
                          "displaced_point");
    }
    const ProjectiveUv p = projective_uv(g, displaced, "reflection", "001", fov);
    return vec3(p.uv, select(p.valid, constant(g, 1.0), constant(g, 0.0)));
}

Expr fourier_series(Graph& g, Expr coefs1, Expr coefs2, Expr ray) {
    OriginScope scope(g, "reflection.fourier_horizon");
    Expr dir = horizontal_direction(g, ray);
    // 003 EvaluateFourier with x = cos t, y = sin t: cos 2t = x^2 - y^2, sin 2t = 2xy,
    // cos 3t = x^3 - 3xy^2, sin 3t = 3x^2 y - y^3, cos 4t = x^4 - 6x^2 y^2 + y^4.
    Expr x = dir.x(), y = dir.y();
    Expr xx = x * x, yy = y * y;
    Expr v = coefs1.x() + coefs1.y() * x + coefs1.z() * y + coefs1.w() * (xx - yy) +
             coefs2.x() * (2.0 * x * y) + coefs2.y() * (x * xx - 3.0 * x * yy) +
             coefs2.z() * (3.0 * xx * y - yy * y) +
             coefs2.w() * (xx * xx - 6.0 * xx * yy + yy * yy);
    return named(v, "horizon_tangent");
}

Expr fourier_sky_weight(Graph& g, Expr coefs1, Expr coefs2, Expr ray) {
    Expr v = fourier_series(g, coefs1, coefs2, ray);
    OriginScope scope(g, "reflection.fourier_horizon");
    // 003 compares hard; +-0.05 (about 3 degrees) anti-aliases the horizon line and bounds the
    // weight's slope in the angle above the horizon to 1.5 / (2 * 0.05) = 15 per radian.
    Expr transition = uniform(g, {.name = "fourier_transition",
                                  .type = Type::Float,
                                  .default_value = {0.05},
                                  .min = 1e-3,
                                  .max = 1.0,
                                  .seed = "003"});
    Expr horizontal = length(ray.xz());
    Expr above = named((ray.y() - v * horizontal) * rsqrt(1.0 + v * v), "above_horizon");
    // The transition is >= 1e-3 by its range; at 0 smoothstep would divide 0 by 0.
    Expr t = max(transition, 1e-3);
    return named(smoothstep(-t, t, above), "sky_weight");
}

Expr fourier_horizon_color(Graph& g, Expr coefs1, Expr coefs2, Expr ray) {
    Expr weight = fourier_sky_weight(g, coefs1, coefs2, ray);
    OriginScope scope(g, "reflection.fourier_horizon");
    // 003: the reflection is dark below the horizon (hills, shore), sky above.
    Expr dark = uniform(g, {.name = "fourier_below_color",
                            .type = Type::Vec3,
                            .default_value = {0.05, 0.07, 0.06},
                            .max = 1e3,
                            .seed = "003"});
    return named(mix(dark, uniform(g, sky_color()), weight), "reflected");
}

namespace {

Expr reflection_sky_cubemap(Surface& s) {
    Expr lookup = sky_cube_lookup(s.g, s.view_ray, s.normal);
    OriginScope scope(s.g, "reflection.sky_cubemap");
    // 001 tints the mirrored lower half with the general water colour (and blurs it offline).
    Expr tint = uniform(s.g, {.name = "reflection_lower_tint",
                              .type = Type::Vec3,
                              .default_value = {0.5, 0.62, 0.66},
                              .max = 1.0,
                              .seed = "001"});
    Expr sky = sample(texture(s.g, sky_cube_texture()), lookup.xyz()).xyz();
    return named(sky * mix(constant(s.g, {1.0, 1.0, 1.0}), tint, lookup.w()), "reflected");
}

Expr reflection_planar_projective(Surface& s) {
    Expr p = planar_reflection_uv(s.g, s.surface_point, s.normal);
    OriginScope scope(s.g, "reflection.planar_projective");
    Expr mirrored = sample(texture(s.g, reflection_map_texture()), p.xy()).xyz();
    // Points on or behind the camera plane have no texel: the constant sky instead.
    return named(select(p.z() > 0.5, mirrored, uniform(s.g, sky_color())), "reflected");
}

Expr reflection_fourier_horizon(Surface& s) {
    Expr uv;
    {
        OriginScope scope(s.g, "reflection.fourier_horizon");
        FullPrecisionScope geometry(s.g);
        Expr origin = uniform(s.g, fourier_map_origin());
        Expr size = uniform(s.g, fourier_map_size());
        uv = named(saturate((s.surface_point.xz() - origin) / size), "fourier_uv");
    }
    OriginScope scope(s.g, "reflection.fourier_horizon");
    Expr coefs1 = sample(texture(s.g, fourier_coefs1_texture()), uv);
    Expr coefs2 = sample(texture(s.g, fourier_coefs2_texture()), uv);
    return fourier_horizon_color(s.g, coefs1, coefs2,
                                 named(reflect(s.view_ray, s.normal), "reflected_ray"));
}

// A choice that reads `source` from the engine and sets the reflected colour with `node`.
ChoiceInfo reflection_choice(ChoiceInfo info, const std::string& source, Expr (*node)(Surface&)) {
    info.compose = [node](Surface& s) { s.reflected = node(s); };
    info.scene_needs = {{SceneFact::ReflectionSource, source, ""}};
    return info;
}

std::vector<CatalogNode> reflection_nodes() {
    using Node = Expr (*)(Graph&, Expr, Expr, Expr);
    const std::vector<NodeInput> fourier_inputs = {
        {"coefs1", Type::Vec4}, {"coefs2", Type::Vec4}, {"ray", Type::Vec3}};
    auto fourier = [&](const std::string& name, const std::string& what, Node f) {
        return CatalogNode{name, what, fourier_inputs, [f](Graph& g, const std::vector<Expr>& in) {
                               return f(g, in[0], in[1], in[2]);
                           }};
    };
    return {
        {"reflection.sky_lookup",
         "001 cube direction reflect(-V, N), lower half mirrored; w = water tint weight",
         {{"view_ray", Type::Vec3}, {"normal", Type::Vec3}},
         [](Graph& g, const std::vector<Expr>& in) { return sky_cube_lookup(g, in[0], in[1]); }},
        {"reflection.projective_uv",
         "001/002 planar reflection uv at P + d N.xz; z = 1 when q.w > 1e-4, else uv = 0.5",
         {{"surface_point", Type::Vec3}, {"normal", Type::Vec3}},
         [](Graph& g, const std::vector<Expr>& in) {
             return planar_reflection_uv(g, in[0], in[1]);
         }},
        fourier("reflection.fourier_series",
                "003 horizon tangent from 8 Fourier coefficients, trig-free", &fourier_series),
        fourier("reflection.fourier_sky_weight", "003 sky (1) or below the horizon (0), smooth",
                &fourier_sky_weight),
        fourier("reflection.fourier_horizon",
                "003 reflected colour: fourier_below_color below the horizon, sky_color above",
                &fourier_horizon_color),
    };
}

} // namespace

AxisInfo reflection_axis() {
    return {
        "reflection",
        "sky_cubemap",
        {
            {.name = "none",
             .description = "constant sky colour",
             .compose =
                 [](Surface& s) {
                     OriginScope scope(s.g, "reflection.none");
                     s.reflected = uniform(s.g, sky_color());
                 }},
            reflection_choice(
                {.name = "sky_cubemap",
                 .seed = "001",
                 .description =
                     "environment cubemap along reflect(-V, N), fallback below the horizon"},
                "cubemap", &reflection_sky_cubemap),
            reflection_choice(
                {.name = "planar_projective",
                 .seed = "001",
                 .description = "planar reflection texture, projective uv displaced by the normal"},
                "planar", &reflection_planar_projective),
            reflection_choice(
                {.name = "fourier_horizon",
                 .seed = "003",
                 .description =
                     "sky above a per-texel horizon from 8 Fourier coefficients, trig-free"},
                "horizon_map", &reflection_fourier_horizon),
        },
        reflection_nodes()};
}

} // namespace watergen
