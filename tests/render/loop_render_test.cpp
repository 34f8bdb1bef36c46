// Loops on lavapipe: a fragment graph whose loop reads a parameter, a captured value and a
// texture (at level 0) and leaves per pixel, built through the whole toolchain in both
// languages and rendered against the CPU evaluator, at 32 and at 16 bits.
#include <catch2/catch.hpp>

#include <cstdio>
#include <set>

#include "shared_runner.h"
#include "watergen/ir/dsl.h"
#include "watergen/pipeline/variant_build.h"
#include "watergen/render/variant_render.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

// March along u until the scene colour's red channel passes a threshold: an early exit that
// differs from pixel to pixel, a texture read per step, a parameter and an outer value.
WaterShader marching_shader(bool relaxed) {
    WaterShader s;
    s.variant = default_variant();
    Graph& g = s.fragment;
    RelaxedScope scope(g, relaxed);
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Expr step_size = uniform(g, {"march_step", Type::Float, {0.013}, 0.001, 0.1, "", "", ""});
    Expr threshold = named(0.25 + 0.5 * uv.y(), "threshold");
    Expr scene = texture(g, scene_color_texture());
    const auto r = loop(g, 48, {uv.x(), constant(g, 0.0)}, [&](Expr, const std::vector<Expr>& c) {
        Expr u = c[0] + step_size;
        Expr red = sample_level(scene, vec2(fract(u), uv.y()), constant(g, 0.0)).x();
        return LoopStep{{u, c[1] + red}, red < threshold};
    });
    g.set_output("color", vec4(fract(r[0]), r[1] * 0.05, threshold, constant(g, 1.0)).id());
    return s;
}

} // namespace

TEST_CASE("a_loop_with_per_pixel_exits_renders_like_the_cpu_evaluates_it", "[render][loop]") {
    const RenderSettings settings{256, 256, 0, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const VariantBuild build = build_shader(marching_shader(false));
    std::string diagnostics;
    for (const auto& d : build.diagnostics)
        diagnostics += format_diagnostic(d) + "\n";
    INFO(diagnostics);
    REQUIRE(build.ok());
    const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
    INFO(r.error);
    REQUIRE(r.ok());
    std::printf("loop render 256x256: glsl-hlsl %.3g, gpu-cpu(float) %.3g, gpu-cpu(double) %.3g\n",
                r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs, r.glsl_vs_cpu_double.max_abs);
    CHECK(r.glsl_vs_hlsl.max_abs == 0);
    // Sums of up to 48 texels in float: the agreement bound of every other render (5e-5).
    CHECK(r.glsl_vs_cpu_float.max_abs <= 5e-5);
    CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
    CHECK(r.validation_messages.empty());
    // The exits differ from pixel to pixel: the march's end point takes many values.
    std::set<float> ends;
    for (size_t p = 0; p < r.gpu_image[0].rgba.size(); p += 4)
        ends.insert(r.gpu_image[0].rgba[p]);
    CHECK(ends.size() > 1000);
}

TEST_CASE("a_loop_in_16_bit_arithmetic_agrees_with_the_cpu_half_model", "[render][loop][half]") {
    const RenderSettings settings{128, 128, 0, false, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    WaterShader shader = marching_shader(true);
    const VariantBuild build = build_shader(shader, EmitOptions{true});
    REQUIRE(build.ok());
    CHECK(build.languages[0].fragment.source.source.find("float16_t") != std::string::npos);
    const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
    INFO(r.error);
    REQUIRE(r.ok());
    const EvalResult half = evaluate_image(shader.fragment, "color", scene.eval_inputs(),
                                           settings.width, settings.height, EvalPrecision::Half);
    REQUIRE(half.ok());
    const ImageRGBA32F cpu = to_image(half, settings.width, settings.height);
    const ImageErrorStats e = compare_images(r.gpu_image[0], cpu);
    std::printf("loop render 16-bit 128x128: gpu-cpu(half) max abs %.3g\n", e.max_abs);
    CHECK(e.nan_inf_pixels == 0);
    CHECK(e.max_abs == 0);
}
