#include "watergen/water/nodes/scene_input.h"

#include <string>

#include "axis_tables.h"
#include "watergen/water/frame.h"
#include "watergen/water/surface.h"
#include "watergen/water/water_shader.h"

namespace watergen {

TextureInput scene_depth_texture() {
    return {"scene_depth", Type::Texture2D, "window depth of the scene surface, in r", ""};
}

namespace {

Parameter convention(const char* name, double value) {
    Parameter p{.name = name, .type = Type::Float, .default_value = {value}, .max = 1.0};
    p.specialization = true;
    p.flag = true;
    return p;
}

} // namespace

Parameter scene_depth_reversed() {
    return convention("scene_depth_reversed", 1.0);
}
Parameter scene_depth_gl_range() {
    return convention("scene_depth_gl_range", 0.0);
}
Parameter scene_ndc_y_up() {
    return convention("scene_ndc_y_up", 0.0);
}
Parameter scene_camera_relative() {
    return convention("scene_camera_relative", 0.0);
}
Parameter scene_sky_depth_margin() {
    return {
        .name = "scene_sky_depth_margin", .type = Type::Float, .default_value = {0.0}, .max = 1.0};
}
Parameter scene_sky_distance() {
    return {.name = "scene_sky_distance",
            .type = Type::Float,
            .default_value = {1000.0},
            .min = 1.0,
            .max = 1e7,
            .unit = "m"};
}
Parameter scene_inv_view_proj_column(int k) {
    std::vector<double> column(4, 0.0);
    column[static_cast<size_t>(k)] = 1.0;
    // The engine's clip-to-world matrix; the host moves what it gives into the frame, unless it
    // gives camera-relative positions (scene_camera_relative).
    return {.name = "scene_inv_view_proj_c" + std::to_string(k),
            .type = Type::Vec4,
            .default_value = column,
            .min = -1e6,
            .max = 1e6,
            .host = {HostRule::FrameClipToWorld, {"scene_camera_relative"}}};
}

SceneFromDepth scene_position_from_depth(Graph& g, Expr uv, Expr eye) {
    OriginScope scope(g, "scene_input.depth_buffer");
    FullPrecisionScope geometry(g);
    Expr depth = named(sample(texture(g, scene_depth_texture()), uv).x(), "scene_depth");
    Expr reversed = uniform(g, scene_depth_reversed()) > 0.5;
    Expr gl_range = uniform(g, scene_depth_gl_range()) > 0.5;
    Expr y_up = uniform(g, scene_ndc_y_up()) > 0.5;
    Expr relative = uniform(g, scene_camera_relative()) > 0.5;
    Expr c[4];
    for (int k = 0; k < 4; ++k)
        c[k] = uniform(g, scene_inv_view_proj_column(k));
    // The depth buffer holds window depth in [0, 1] under every convention; the far value is
    // what the engine clears it to, so a pixel the scene never drew is sky.
    Expr far_depth = select(reversed, constant(g, 0.0), constant(g, 1.0));
    Expr sky = named(abs(depth - far_depth) <= uniform(g, scene_sky_depth_margin()), "scene_sky");
    Expr ndc_x = uv.x() * 2.0 - 1.0;
    Expr ndc_y = named(select(y_up, 1.0 - uv.y() * 2.0, uv.y() * 2.0 - 1.0), "scene_ndc_y");
    Expr ndc_z = named(select(gl_range, depth * 2.0 - 1.0, depth), "scene_ndc_z");
    // An infinite reversed projection puts the clear value at w = 0: such a pixel is sky and
    // takes w = 1, so no division by zero reaches either branch.
    Expr q = named(c[0] * ndc_x + c[1] * ndc_y + c[2] * ndc_z + c[3], "scene_clip");
    Expr q_w = named(select(sky, constant(g, 1.0), q.w()), "scene_clip_w");
    Expr p = named(q.xyz() / q_w, "scene_unprojected");
    Expr drawn = named(select(relative, p, p - eye), "scene_depth_to_scene");
    // The sky pixel's ray: through the point at window depth 0.5, finite in every projection.
    Expr mid_z = select(gl_range, constant(g, 0.0), constant(g, 0.5));
    Expr m = named(c[0] * ndc_x + c[1] * ndc_y + c[2] * mid_z + c[3], "scene_mid_clip");
    Expr mid = m.xyz() / m.w();
    Expr ray = normalize(select(relative, mid, mid - eye));
    Expr to_scene = named(select(sky, ray * uniform(g, scene_sky_distance()), drawn), "to_scene");
    return {named(select(relative || sky, eye + to_scene, p), "scene_pos"), to_scene};
}

AxisInfo scene_input_axis() {
    const NodeInput inputs[] = {{"uv", Type::Vec2}, {"eye", Type::Vec3}};
    AxisInfo axis{
        "scene_input",
        "position_texture",
        {
            {.name = "position_texture",
             .description = "scene position from the scene_position texture the engine writes, "
                            "relative to the eye",
             .compose =
                 [](Surface& s) {
                     OriginScope scope(s.g, "surface");
                     // The texture holds the scene point less the eye (what a large-world
                     // engine's G-buffer holds): exact in float near the eye at any distance
                     // from the world origin, where a world position would keep centimetres.
                     s.to_scene = named(sample(texture(s.g, scene_position_texture()), s.uv).xyz(),
                                        "to_scene");
                     s.scene_pos = named(s.eye + s.to_scene, "scene_pos");
                 },
             .scene_needs = {{SceneFact::SceneInput, "position_texture", ""}}},
            feature_choice(
                {.name = "depth_buffer",
                 .description = "world position unprojected from the depth buffer (conventions: "
                                "reversed Z, NDC z range, NDC y, camera-relative)",
                 .scene_needs = {{SceneFact::SceneInput, "depth_buffer", ""}}},
                ChoiceNode{{inputs, inputs + 2},
                           [](Graph& g, const std::vector<Expr>& in) {
                               return scene_position_from_depth(g, in[0], in[1]).position;
                           },
                           "reads scene_depth"},
                [](Surface& s) {
                    const SceneFromDepth scene = scene_position_from_depth(s.g, s.uv, s.eye);
                    s.scene_pos = scene.position;
                    s.to_scene = scene.to_scene;
                }),
        }};
    // Keys and file names of every variant from before the axis stay as they were.
    axis.keyed_at_default = false;
    axis.permutation_only = true; // a pass binds a depth buffer or a position texture
    return axis;
}

} // namespace watergen
