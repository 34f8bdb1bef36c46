// The build modes draw the same images: variants of the default material rendered from their own
// shader (permutations) and from the shared shader of their precision with the axes switched by
// specialization constants (specialized) or by uniform-block members (branching), at 256x256
// through both language paths; the CPU evaluator of the shared graph agrees as well.
#include <catch2/catch.hpp>

#include <algorithm>

#include "build_test_support.h"
#include "shared_runner.h"
#include "watergen/eval/compare/prune_measure.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/material.h"

using namespace watergen;

namespace {

const RenderSettings kSettings{256, 256, 0, false, true};

// A few variants spread over the material's space, full and half precision.
std::vector<Variant> some_variants(const Material& m) {
    std::vector<Variant> all;
    enumerate(m.space, [&](const Variant& v) { all.push_back(v); });
    std::sort(all.begin(), all.end(),
              [](const Variant& a, const Variant& b) { return a.key() < b.key(); });
    REQUIRE(all.size() == 144);
    return {all[0], all[47], all[95], all[143]};
}

VariantBuild checked_build(WaterShader shader) {
    VariantBuild b = build_shader(std::move(shader));
    std::string diagnostics;
    for (const auto& d : b.diagnostics)
        diagnostics += format_diagnostic(d) + "\n";
    INFO(diagnostics);
    REQUIRE(b.ok());
    return b;
}

VariantRender checked_render(const VariantBuild& b, const SyntheticScene& scene) {
    test::shared_runner().clear_validation_messages();
    VariantRender r = render_variant(test::shared_runner(), b, scene, kSettings);
    INFO(r.error);
    REQUIRE(r.ok());
    CHECK(r.validation_messages.empty());
    return r;
}

} // namespace

TEST_CASE("specialized_and_branching_shaders_draw_what_the_permutations_draw", "[modes]") {
    const Material m = default_material();
    const std::vector<Variant> variants = some_variants(m);
    const SyntheticScene scene = make_synthetic_scene(kSettings.width, kSettings.height);
    for (BuildMode mode : {BuildMode::Specialized, BuildMode::Branching}) {
        std::vector<Variant> space;
        enumerate(m.space, [&](const Variant& v) { space.push_back(v); });
        const std::vector<ShaderChoices> shaders = shaders_for(space, mode);
        REQUIRE(shaders.size() == 2); // one per precision
        // Half precision offers Schlick only (the material's rule): no fresnel switch there.
        // Sorted by key: "fresnel=schlick," (half) before "fresnel=schlick|exact," (full).
        using Axes = std::vector<std::string>;
        CHECK(shaders[1].switched_axes() ==
              Axes{"fresnel", "specular", "foam", "reflection", "waves", "shore", "caustics"});
        CHECK(shaders[0].switched_axes() ==
              Axes{"specular", "foam", "reflection", "waves", "shore", "caustics"});
        std::vector<VariantBuild> shared;
        for (const ShaderChoices& s : shaders)
            shared.push_back(checked_build(m.compose(s)));
        for (const Variant& v : variants) {
            INFO(to_string(mode) << " " << v.key());
            const auto it = std::find_if(shaders.begin(), shaders.end(),
                                         [&](const ShaderChoices& s) { return s.covers(v); });
            REQUIRE(it != shaders.end());
            SyntheticScene selected = scene;
            for (const auto& [name, value] : it->selector_values(v))
                selected.uniforms[name] = {value};
            const VariantRender own = checked_render(checked_build(m.compose(v)), scene);
            const VariantRender one =
                checked_render(shared[static_cast<size_t>(it - shaders.begin())], selected);
            for (size_t lang = 0; lang < 2; ++lang) {
                const ImageErrorStats d = compare_images(one.gpu_image[lang], own.gpu_image[lang]);
                INFO("language path " << lang);
                REQUIRE(d.error.empty());
                CHECK(d.nan_inf_pixels == d.reference_nan_inf_pixels);
                CHECK(d.max_abs <= 1e-6);
            }
            CHECK(one.glsl_vs_hlsl.max_abs <= 1e-6);
            // The CPU evaluator runs the same operations on the selected case: the same image.
            CHECK(compare_images(one.cpu_float, own.cpu_float).max_abs == 0.0);
        }
    }
}

TEST_CASE("a_branching_shader_folded_under_a_scene_draws_what_it_draws_unfolded", "[modes]") {
    // mountain_lake's facts fold inside the shared shader's cases (time = 0, world_to_meters,
    // the depth and height ranges); drawn in the scene conformed to them, the folded shader
    // must give the unfolded one's pixels for each variant it serves.
    const Material m = default_material();
    Diagnostics ds;
    const auto facts = load_scene(test::source_dir() + "/examples/scenes/mountain_lake.json", ds);
    REQUIRE(facts);
    const auto plan = plan_scene(m, *facts, ds);
    REQUIRE(plan);
    const std::vector<ShaderChoices> shaders = shaders_for(
        std::vector<Variant>(plan->variants.begin(), plan->variants.end()), BuildMode::Branching);
    REQUIRE(shaders.size() == 1); // the lake targets half precision only
    WaterShader unfolded = m.compose(shaders[0]);
    WaterShader folded = unfolded;
    FoldResult f = fold_graph(folded.fragment, plan->facts);
    folded.fragment = std::move(f.graph);
    const VariantBuild a = checked_build(unfolded), b = checked_build(folded);
    CHECK(b.languages[0].fragment.toolchain.instruction_count_optimized <
          a.languages[0].fragment.toolchain.instruction_count_optimized);
    const SyntheticScene scene =
        conform_scene(make_synthetic_scene(kSettings.width, kSettings.height), *plan, m);
    for (const Variant& v : {plan->variants.front(), plan->variants.back()}) {
        INFO(v.key());
        SyntheticScene selected = scene;
        for (const auto& [name, value] : shaders[0].selector_values(v))
            selected.uniforms[name] = {value};
        const VariantRender x = checked_render(a, selected), y = checked_render(b, selected);
        for (size_t lang = 0; lang < 2; ++lang) {
            const ImageErrorStats d = compare_images(y.gpu_image[lang], x.gpu_image[lang]);
            REQUIRE(d.error.empty());
            CHECK(d.nan_inf_pixels == d.reference_nan_inf_pixels);
            CHECK(d.max_abs == 0.0);
        }
    }
}
