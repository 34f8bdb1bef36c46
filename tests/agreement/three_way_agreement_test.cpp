#include <catch2/catch.hpp>

#include <cstdio>

#include "watergen/variant_render.h"

using namespace watergen;

namespace {

VulkanRunner& runner() {
    static std::unique_ptr<VulkanRunner> r = [] {
        std::string error;
        auto created = VulkanRunner::create({}, &error);
        if (!created) FAIL("no Vulkan device: " << error);
        return created;
    }();
    return *r;
}

} // namespace

// Every wired variant through both language paths on lavapipe, against the CPU evaluator.
TEST_CASE("glsl_hlsl_and_cpu_agree_for_every_variant", "[render]") {
    const RenderSettings settings{128, 128, 2, true};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    for (const Variant& v : all_variants()) {
        INFO(v.key());
        const VariantBuild build = build_variant(v);
        REQUIRE(build.ok());
        const VariantRender r = render_variant(runner(), build, scene, settings);
        REQUIRE(r.ok());
        std::printf("%-44s glsl-hlsl %.3g  gpu-cpu(float) %.3g  gpu-cpu(double) %.3g  pipeline %.1f ms first %.1f ms steady %.3f ms\n",
                    v.key().c_str(), r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs, r.glsl_vs_cpu_double.max_abs,
                    r.gpu[0].pipeline_ms, r.gpu[0].first_draw_ms, r.gpu[0].steady_draw_ms);
        CHECK(r.validation_messages.empty());
        CHECK(r.glsl_vs_hlsl.max_abs <= 1e-6);
        CHECK(r.glsl_vs_cpu_float.max_abs <= 1e-4);
        CHECK(r.hlsl_vs_cpu_float.max_abs <= 1e-4);
        CHECK(r.gpu_image[0].rgba.size() == 128u * 128u * 4u);
        CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK(r.hlsl_vs_cpu_float.nan_inf_pixels == 0);
        CHECK_FALSE(is_degenerate(r.gpu_image[0]));
    }
}
