// Surface normals: flat, central differences of the height map and a detail normal map in a
// derivative tangent frame (000), and the analytic normal of the wave model (004).
#include "watergen/water/nodes/normals.h"

#include "axis_tables.h"
#include "watergen/water/frame.h"
#include "watergen/water/nodes/waves.h"
#include "watergen/water/surface.h"

namespace watergen {

Expr normal_from_slope(Graph& g, Expr slope) {
    FullPrecisionScope full(g);
    // y = 1: never a zero vector, so a plain normalize is safe.
    return named(normalize(vec3(-slope.x(), constant(g, 1.0), -slope.y())), "wave_normal");
}

TextureInput detail_normal_map_texture() {
    return {"detail_normal_map", Type::Texture2D,
            "tangent-space normals, rgb = 0.5 n + 0.5; periodic tile, texel k at k / (n - 1)", ""};
}

TangentFrame derivative_tangent_frame(Graph& g, Expr position, Expr uv) {
    FullPrecisionScope full(g);
    const double tiny = 1e-24;
    Expr dp1 = ddx(position), dp2 = ddy(position);
    Expr duv1 = ddx(uv), duv2 = ddy(uv);
    // The frame is homogeneous of degree 4 in a common scale of dp and duv (uv is linear in
    // position): dividing both by the larger |dp| leaves the directions alone and keeps a far
    // pixel (|dp| ~ 1e6 m near the horizon) from overflowing float in the products below.
    Expr m = named(max(max(length(dp1), length(dp2)), 1e-30), "frame_scale");
    dp1 = dp1 / m;
    dp2 = dp2 / m;
    duv1 = duv1 / m;
    duv2 = duv2 / m;
    // Schuler: M = (dp1, dp2, dp1 x dp2) as rows; the first two rows of its adjugate map the
    // screen-space uv derivatives to world-space gradients of u and v.
    Expr n = cross(dp1, dp2);
    Expr r1 = named(cross(dp2, n), "frame_row1"), r2 = named(cross(n, dp1), "frame_row2");
    Expr t = named(duv1.x() * r1 + duv2.x() * r2, "frame_tangent");
    Expr b = named(duv1.y() * r1 + duv2.y() * r2, "frame_binormal");
    Expr tt = dot(t, t), bb = dot(b, b);
    // Vanishing uv derivatives (or position derivatives) leave no frame: the caller falls
    // back to the geometric normal. NaN compares false and falls back too.
    Expr valid = named(min(tt, bb) > tiny, "frame_valid");
    return {named(t * rsqrt(max(tt, tiny)), "frame_t"), named(b * rsqrt(max(bb, tiny)), "frame_b"),
            valid};
}

Expr detail_normal(Graph& g, Expr base, Expr position, Expr time) {
    FullPrecisionScope full(g);
    const Parameter scale_parameter{.name = "detail_scale",
                                    .type = Type::Vec2,
                                    .default_value = {0.25, 0.6},
                                    .max = 100.0,
                                    .unit = "1/m",
                                    .seed = "000"};
    const Parameter scroll_parameter{.name = "detail_scroll",
                                     .type = Type::Vec4,
                                     .default_value = {0.02, 0.01, -0.015, 0.025},
                                     .min = -10.0,
                                     .max = 10.0,
                                     .unit = "1/s",
                                     .seed = "000"};
    Expr scale = uniform(g, scale_parameter);
    Expr scroll = uniform(g, scroll_parameter);
    Expr strength = uniform(g, {.name = "detail_strength",
                                .type = Type::Float,
                                .default_value = {0.6},
                                .max = 10.0,
                                .seed = "000"});
    Expr texels = uniform(g, {.name = "detail_texels",
                              .type = Type::Float,
                              .default_value = {64.0},
                              .min = 2.0,
                              .max = 16384.0,
                              .unit = "texels",
                              .seed = "000"});
    Expr map = texture(g, detail_normal_map_texture());
    Expr zero = constant(g, 0.0);
    // 000: "the normal map has to be sampled several times with texture coordinates varying
    // over time": two layers; the second only rescales uv, so it shares the first's frame.
    // With the scene's clock the position is in the frame (frame.h): the host adds c scale +
    // scroll t, each pair reduced mod 1.
    Expr offset = is_scene_clock(time)
                      ? scroll_offset(g, "detail_uv_offset", scale_parameter, scroll_parameter)
                      : vec4(time * scroll.xy(), time * scroll.swizzle("zw"));
    Expr uv1 = named(position.xz() * scale.x() + offset.xy(), "detail_uv");
    Expr uv2 = named(position.xz() * scale.y() + offset.swizzle("zw"), "detail_uv2");
    // The sampler has one mip level: where a pixel spans a good part of a tile the map would
    // alias into noise, so each layer's tangential part fades out as its uv footprint per pixel
    // grows to detail_max_footprint (1/8 tile: Nyquist for the map's 4 cycles per tile).
    Expr max_footprint = uniform(g, {.name = "detail_max_footprint",
                                     .type = Type::Float,
                                     .default_value = {0.125},
                                     .min = 1e-6,
                                     .max = 1e3,
                                     .unit = "tiles/pixel",
                                     .seed = "000"});
    auto layer = [&](Expr uv, const char* name) {
        Expr footprint = max(length(ddx(uv)), length(ddy(uv)));
        Expr keep = saturate(1.0 - footprint / max_footprint);
        Expr texel = sample_level(map, tile_coordinate(uv, texels), zero).xyz() * 2.0 - 1.0;
        return named(vec3(texel.xy() * keep, texel.z()), name);
    };
    Expr t = named(layer(uv1, "detail_layer") + layer(uv2, "detail_layer2"), "detail_texel");
    const TangentFrame frame = derivative_tangent_frame(g, position, uv1);
    Expr n =
        frame.tangent * (t.x() * strength) + frame.binormal * (t.y() * strength) + base * t.z();
    // Texels decoding to zero (0.5 grey) give a zero vector: keep the base normal.
    return named(select(frame.valid, safe_normalize(n, base), base), "detail_normal");
}

namespace {

// A choice whose node runs under its own origin, in the catalog and in the water pass.
ChoiceInfo normals_choice(ChoiceInfo info, std::vector<NodeInput> inputs,
                          std::function<Expr(Graph&, const std::vector<Expr>&)> node,
                          std::function<Expr(Surface&)> compose, std::string note = "") {
    const std::string origin = "normals." + info.name;
    return feature_choice(std::move(info),
                          ChoiceNode{std::move(inputs),
                                     [origin, node](Graph& g, const std::vector<Expr>& in) {
                                         OriginScope scope(g, origin);
                                         return node(g, in);
                                     },
                                     std::move(note)},
                          [origin, compose](Surface& s) {
                              OriginScope scope(s.g, origin);
                              if (Expr n = compose(s); n.valid()) s.normal = n;
                          });
}

Expr analytic_normal(Surface& s) {
    if (!s.wave_slope.valid()) {
        s.g.error(
            "normals: 'analytic' needs a wave model with derivatives (sum_of_sines, gerstner)");
        return Expr();
    }
    return normal_from_slope(s.g, s.wave_slope);
}

Expr detail_map_normal(Surface& s) {
    // The base is the wave model's own normal when it has one, else the plane's.
    Expr base = s.wave_slope.valid() ? normal_from_slope(s.g, s.wave_slope)
                                     : constant(s.g, {0.0, 1.0, 0.0});
    return detail_normal(s.g, base, s.surface_point, s.time);
}

} // namespace

AxisInfo normals_axis() {
    return {
        "normals",
        "flat",
        {
            normals_choice(
                {.name = "flat", .description = "(0, 1, 0)"}, {{"xz", Type::Vec2}},
                [](Graph& g, const std::vector<Expr>&) {
                    return constant(g, {0.0, 1.0, 0.0});
                },
                [](Surface& s) {
                    return constant(s.g, {0.0, 1.0, 0.0});
                }),
            normals_choice(
                {.name = "heightmap_diff",
                 .seed = "000",
                 .description = "central differences of the height map"},
                {{"xz", Type::Vec2}, {"time", Type::Float}},
                [](Graph& g, const std::vector<Expr>& in) {
                    return heightmap_normal(g, in[0], in[1]);
                },
                [](Surface& s) {
                    return heightmap_normal(s.g, s.surface_point.xz(), s.time, pixel_footprint(s));
                },
                "reads texture height_map"),
            normals_choice(
                {.name = "detail_map",
                 .seed = "000",
                 .description = "detail normal map in a derivative tangent frame (Schuler)"},
                {{"base", Type::Vec3}, {"position", Type::Vec3}, {"time", Type::Float}},
                [](Graph& g, const std::vector<Expr>& in) {
                    return detail_normal(g, in[0], in[1], in[2]);
                },
                &detail_map_normal,
                "base normal perturbed at position; needs ddx/ddy over 2x2 quads and texture "
                "detail_normal_map"),
            // The catalog node takes the slope as input: any height field's exact normal.
            normals_choice(
                {.name = "analytic",
                 .seed = "004",
                 .description = "exact normal of the wave model",
                 .gold = true,
                 .requirements =
                     {{"waves",
                       {"sum_of_sines", "gerstner"},
                       "analytic normals are the derivatives of a closed-form wave model"}}},
                {{"slope", Type::Vec2}},
                [](Graph& g, const std::vector<Expr>& in) { return normal_from_slope(g, in[0]); },
                &analytic_normal),
        }};
}

} // namespace watergen
