#include "watergen/eval/draw/caustics_bottom.h"

#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/water/axis_registry.h"
#include "watergen/water/water_shader.h"

namespace watergen {

ImageRGBA32F caustics_lit_bottom(const std::string& caustics_choice, const SyntheticScene& scene,
                                 std::string* error) {
    // The choice's own catalog node (axis_registry.h): the lit colour from (colour, bottom xz).
    const AxisInfo* axis = find_axis("caustics");
    const ChoiceInfo* choice = axis ? find_choice(*axis, caustics_choice) : nullptr;
    if (!choice || !choice->node) {
        *error = "caustics=" + caustics_choice + " lights no bottom";
        return {};
    }
    Graph g;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Expr rgb = sample(texture(g, scene_color_texture()), uv).xyz();
    // The texel is the bottom less the eye (scene_input.h): the eye puts it back in the frame.
    Expr pos = scene_eye_position(g) + sample(texture(g, scene_position_texture()), uv).xyz();
    // The water shader's own parameter: the scene sets it (0 in every view).
    Expr level = scene_water_level(g);
    Expr lit = choice->node->build(g, {rgb, pos.xz()});
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
