// Loops on lavapipe: a fragment graph whose loop reads a parameter, a captured value and a
// texture (at level 0) and leaves per pixel, built through the whole toolchain in both
// languages and rendered against the CPU evaluator, at 32 and at 16 bits; a loop over an
// array parameter (a sum of sines whose waves are data), with a trip count from a parameter
// (a uniform or a specialization constant).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/pipeline/variant/variant_build.h"
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
    Expr step_size = uniform(g, {.name = "march_step",
                                 .type = Type::Float,
                                 .default_value = {0.013},
                                 .min = 0.001,
                                 .max = 0.1});
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

// A sum of four sines, one per element of a vec4 array: amplitude, two frequencies, phase;
// `counted`: as many as parameter wave_count says (at most 4).
WaterShader wave_table_shader(bool counted = false) {
    WaterShader s;
    s.variant = default_variant();
    Graph& g = s.fragment;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Parameter table{.name = "wave_table", .type = Type::Vec4, .min = -40.0, .max = 40.0};
    table.array_size = 4;
    table.default_value = {0.5,   7.0,  3.0,  0.1, 0.25,   -11.0, 17.0, 2.0,
                           0.125, 23.0, -5.0, 4.0, 0.0625, 31.0,  37.0, -1.5};
    auto wave = [&](Expr i, const std::vector<Expr>& c) {
        Expr w = element(table, i);
        return LoopStep{{c[0] + w.x() * sin(w.y() * uv.x() + w.z() * uv.y() + w.w())}, Expr()};
    };
    const auto r = counted ? loop(g,
                                  uniform(g, {.name = "wave_count",
                                              .type = Type::Float,
                                              .default_value = {4.0},
                                              .max = 4.0}),
                                  4, {constant(g, 0.0)}, wave)
                           : loop(g, 4, {constant(g, 0.0)}, wave);
    g.set_output("color", vec4(r[0], uv.x(), uv.y(), constant(g, 1.0)).id());
    return s;
}

} // namespace

TEST_CASE("a_loop_over_an_array_parameter_renders_like_the_cpu_evaluates_it",
          "[render][loop][array]") {
    const RenderSettings settings{128, 128, 0, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const VariantBuild build = build_shader(wave_table_shader());
    std::string diagnostics;
    for (const auto& d : build.diagnostics)
        diagnostics += format_diagnostic(d) + "\n";
    INFO(diagnostics);
    REQUIRE(build.ok());
    // One descriptor layout: both languages' modules reflect the block the generator laid out.
    const UniformLayout& layout = build.languages[0].fragment.source.interface.uniforms;
    for (const auto& language : build.languages) {
        const auto& bindings = language.fragment.toolchain.reflection.bindings;
        REQUIRE_FALSE(bindings.empty());
        const DescriptorBinding& block = bindings[0];
        CHECK(block.name == "WaterParams");
        CHECK(block.block_size == layout.size);
        REQUIRE(block.members.size() == 1);
        CHECK(block.members[0].name == "wave_table");
        CHECK(block.members[0].type == "vec4[4]");
        CHECK(block.members[0].offset == 0);
        CHECK(block.members[0].size == 64);
        CHECK(block.members[0].array_size == 4);
        CHECK(block.members[0].array_stride == kArrayStride);
    }
    const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
    INFO(r.error);
    REQUIRE(r.ok());
    std::printf("array loop 128x128: glsl-hlsl %.3g, gpu-cpu(float) %.3g\n", r.glsl_vs_hlsl.max_abs,
                r.glsl_vs_cpu_float.max_abs);
    CHECK(r.glsl_vs_hlsl.max_abs == 0);
    // Four sines of arguments up to ~70 summed in float: the agreement bound of every other
    // render (5e-5), which the sines' Vulkan precision sets.
    CHECK(r.glsl_vs_cpu_float.max_abs <= 5e-5);
    CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
    CHECK(r.validation_messages.empty());
    // Every element was read: the image is not the first wave's alone.
    const EvalResult first_only = [&] {
        WaterShader one = wave_table_shader();
        std::vector<double> table = one.fragment.find_parameter("wave_table")->default_value;
        std::fill(table.begin() + 4, table.end(), 0.0);
        EvalInputs in = scene.eval_inputs();
        in.uniforms["wave_table"] = table;
        return evaluate_image(one.fragment, "color", in, settings.width, settings.height,
                              EvalPrecision::Float);
    }();
    REQUIRE(first_only.ok());
    const ImageErrorStats differ =
        compare_images(r.gpu_image[0], to_image(first_only, settings.width, settings.height));
    CHECK(differ.max_abs > 0.1);
}

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

namespace {

constexpr uint32_t kUnroll = 0x1, kDontUnroll = 0x2; // SPIR-V LoopControl bits

// The LoopControl operand of every OpLoopMerge (opcode 246) in the compiled module.
std::vector<uint32_t> loop_controls(const StageBuild& stage) {
    const std::vector<uint32_t>& words = stage.toolchain.spirv;
    std::vector<uint32_t> out;
    for (size_t i = 5; i < words.size();) {
        const uint32_t count = words[i] >> 16, opcode = words[i] & 0xffff;
        if (opcode == 246 && i + 3 < words.size()) out.push_back(words[i + 3]);
        i += count ? count : 1;
    }
    return out;
}

} // namespace

TEST_CASE("unrolled_loops_render_the_kept_loops_image", "[render][loop]") {
    // The unroll hint is a compiler hint only: spirv-opt unrolls [[unroll]] loops, and with
    // the loop index a constant in each copy the compilers fold and reorder a few roundings
    // (measured: Gerstner up to 3.1e-7, a few ulps of the colour), far inside the GPU-CPU
    // agreement bound (5e-5). The loop-heaviest waves choices at 256x256.
    const RenderSettings settings{256, 256, 0, false, false};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (const char* waves : {"gerstner", "heightmap_march_converged"}) {
        Variant v = default_variant();
        set_choice(v, "waves", waves);
        const VariantBuild kept =
            build_variant(v, nullptr, EmitOptions{false, {}, LoopUnroll::None});
        const VariantBuild unrolled =
            build_variant(v, nullptr, EmitOptions{false, {}, LoopUnroll::All});
        REQUIRE(kept.ok());
        REQUIRE(unrolled.ok());
        // The hint reached SPIR-V: every OpLoopMerge says Unroll, or DontUnroll. (spirv-opt
        // unrolls only constant-count loops; a wave loop counted by wave_count stays.)
        for (const auto* b : {&kept, &unrolled}) {
            const std::vector<uint32_t> controls = loop_controls(b->languages[0].fragment);
            CHECK(!controls.empty());
            for (uint32_t c : controls)
                CHECK(c == (b == &kept ? kDontUnroll : kUnroll));
        }
        const VariantRender a = render_variant(test::shared_runner(), kept, scene, settings);
        const VariantRender b = render_variant(test::shared_runner(), unrolled, scene, settings);
        INFO(waves << ": " << a.error << b.error);
        REQUIRE(a.ok());
        REQUIRE(b.ok());
        for (int lang = 0; lang < 2; ++lang) {
            const double diff = compare_images(a.gpu_image[lang], b.gpu_image[lang]).max_abs;
            std::printf("%s, path %d: kept vs unrolled max abs %.3g\n", waves, lang, diff);
            CHECK(diff <= 1e-6);
        }
    }
}

TEST_CASE("a_trip_count_from_a_uniform_or_a_specialization_constant_renders_like_the_cpu",
          "[render][loop][array]") {
    const RenderSettings settings{64, 64, 0, false};
    SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const EvalResult all_four =
        evaluate_image(wave_table_shader().fragment, "color", scene.eval_inputs(), settings.width,
                       settings.height, EvalPrecision::Float);
    REQUIRE(all_four.ok());
    for (const bool constant : {false, true}) {
        const VariantBuild build =
            build_shader(wave_table_shader(true),
                         EmitOptions{false, constant ? std::set<std::string>{"wave_count"}
                                                     : std::set<std::string>{}});
        REQUIRE(build.ok());
        const std::string& glsl = build.languages[0].fragment.source.source;
        CHECK((glsl.find("floor(params.wave_count)") != std::string::npos) == !constant);
        // 2.5 runs two waves; NaN and 0 none (the colour's red is 0), 9 all four.
        for (const double count : {0.0, 1.0, 2.5, 4.0, 9.0, double(NAN)}) {
            scene.uniforms["wave_count"] = {count};
            const VariantRender r = render_variant(test::shared_runner(), build, scene, settings);
            INFO(r.error << " count " << count << (constant ? " (constant)" : " (uniform)"));
            REQUIRE(r.ok());
            std::printf("counted loop, count %g%s: glsl-hlsl %.3g, gpu-cpu(float) %.3g\n", count,
                        constant ? " (constant)" : "", r.glsl_vs_hlsl.max_abs,
                        r.glsl_vs_cpu_float.max_abs);
            CHECK(r.glsl_vs_hlsl.max_abs == 0);
            CHECK(r.glsl_vs_cpu_float.max_abs <= 5e-5);
            CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
            CHECK(r.validation_messages.empty());
            double max_red = 0;
            for (size_t p = 0; p < r.gpu_image[0].rgba.size(); p += 4)
                max_red = std::max(max_red, double(std::fabs(r.gpu_image[0].rgba[p])));
            CHECK((max_red == 0) == !(count >= 1));
            const ImageErrorStats from_all_four =
                compare_images(r.gpu_image[0], to_image(all_four, settings.width, settings.height));
            if (count >= 4)
                CHECK(from_all_four.max_abs <= 5e-5);
            else
                CHECK(from_all_four.max_abs > 0.01);
        }
    }
}
