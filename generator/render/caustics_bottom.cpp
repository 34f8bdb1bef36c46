#include "watergen/render/caustics_bottom.h"

#include "watergen/ir/dsl.h"
#include "watergen/render/variant_render.h"
#include "watergen/water/nodes/caustics.h"
#include "watergen/water/water_shader.h"

namespace watergen {

namespace {

using IntensityNode = Expr (*)(Graph&, Expr);

IntensityNode intensity_node(const std::string& choice) {
    if (choice == "texture") return &caustics_texture_intensity;
    if (choice == "area_ratio") return &caustics_area_ratio_intensity;
    if (choice == "photon_splat") return &caustics_photon_splat_intensity;
    return nullptr;
}

} // namespace

ImageRGBA32F caustics_lit_bottom(const std::string& caustics_choice, const SyntheticScene& scene,
                                 std::string* error) {
    const IntensityNode intensity = intensity_node(caustics_choice);
    if (!intensity) {
        *error = "caustics=" + caustics_choice + " lights no bottom";
        return {};
    }
    Graph g;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Expr rgb = sample(texture(g, scene_color_texture()), uv).xyz();
    Expr pos = sample(texture(g, scene_position_texture()), uv).xyz();
    // The water shader's own parameter: the scene sets it (0 in every view).
    Expr level = uniform(g, {"water_level", Type::Float, {0.0}, -1e5, 1e5, "m", "000", ""});
    Expr lit = caustics_lit(g, rgb, intensity(g, pos.xz()));
    g.set_output("color", vec4(select(pos.y() < level, lit, rgb), constant(g, 1.0)).id());
    const EvalResult r = evaluate_image(g, "color", scene.eval_inputs(), scene.width, scene.height,
                                        EvalPrecision::Float);
    if (!r.ok()) {
        *error = "lit bottom: " + r.error;
        return {};
    }
    return to_image(r, scene.width, scene.height);
}

} // namespace watergen
