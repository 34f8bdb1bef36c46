#include "watergen/water_shader.h"

#include "watergen/nodes.h"

namespace watergen {

TextureInput scene_color_texture() {
    return {"scene_color", Type::Texture2D, "lit colour of the scene under the water, linear rgb", ""};
}

TextureInput scene_position_texture() {
    return {"scene_position", Type::Texture2D, "world position of the scene surface, xyz in m", ""};
}

namespace {

Expr apply_fresnel(Graph& g, const std::string& choice, Expr c) {
    if (choice == "none") return fresnel_none(g, c);
    if (choice == "exact") return fresnel_exact(g, c);
    return fresnel_schlick(g, c);
}

Expr apply_extinction(Graph& g, const std::string& choice, const ExtinctionInputs& in) {
    if (choice == "none") return extinction_none(g, in);
    return extinction_absorb_scatter(g, in);
}

} // namespace

WaterShader build_water_shader(const Variant& variant) {
    WaterShader shader{variant, Graph{}};
    Graph& g = shader.fragment;

    OriginScope scope(g, "surface");
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Expr scene = named(sample(texture(g, scene_color_texture()), uv).xyz(), "scene_rgb");
    Expr position = named(sample(texture(g, scene_position_texture()), uv).xyz(), "scene_pos");
    Expr eye = uniform(g, {"eye_position", Type::Vec3, {0.0, 8.0, -30.0}, -1e5, 1e5, "m", "000", ""});
    Expr level = uniform(g, {"water_level", Type::Float, {0.0}, -1e5, 1e5, "m", "000", ""});
    Expr sky = uniform(g, {"sky_color", Type::Vec3, {0.55, 0.7, 0.9}, 0.0, 1e3, "", "000", ""});

    // 000: intersect the eye ray towards the scene point with the water plane.
    Expr to_scene = position - eye;
    Expr distance = named(length(to_scene), "scene_distance");
    Expr ray = named(to_scene / max(distance, 1e-6), "view_ray");
    // A water pixel's ray points down (the scene lies below the plane); clamping its y keeps
    // the division finite for a horizontal ray without changing any water pixel.
    Expr ray_down = named(min(ray.y(), -1e-6), "view_ray_y");
    Expr hit = named(max((level - eye.y()) / ray_down, 0.0), "surface_distance");
    Expr path = named(max(distance - hit, 0.0), "water_path");
    Expr depth = named(max(level - position.y(), 0.0), "water_depth");

    Expr normal = constant(g, {0.0, 1.0, 0.0}); // flat water surface
    Expr to_eye = -ray;
    Expr cos_view = named(dot(normal, to_eye), "n_dot_v");

    Expr fresnel = apply_fresnel(g, variant.choice("fresnel"), cos_view);
    Expr refracted = apply_extinction(g, variant.choice("extinction"), {depth, path, scene});

    OriginScope compose(g, "compose");
    Expr water = named(mix(refracted, sky, fresnel), "water_rgb");
    Expr is_water = position.y() < level;
    Expr rgb = select(is_water, water, scene);
    g.set_output("color", vec4(rgb, constant(g, 1.0)).id());
    return shader;
}

} // namespace watergen
