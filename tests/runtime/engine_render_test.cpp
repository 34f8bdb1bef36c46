// A variant drawn through the engine runtime library (a build directory opened with
// ShaderBuild, uniforms packed by UniformWriter, the pipeline from VariantPipeline, drawn on the
// library's HeadlessDevice) gives the same image as `watergen render` (the variant built in-process
// and drawn by the test runner from make_render_job): max abs 0 through both language paths.
// And the pipeline cache file: written by one run, accepted by the next, same image.
#include <catch2/catch.hpp>

#include <cmath>

#include "engine_builds.h"
#include "engine_draw_support.h"
#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/headless/headless_device.h"
#include "watergen/runtime/uniform_writer.h"
#include "watergen/water/presets.h"

using namespace watergen;
using namespace watergen::test;

namespace {

constexpr uint32_t kSize = 96;

// The variant with the most to draw: exact Fresnel, specular, shore foam, sky cube map, Gerstner
// waves (arrays in the block), soft shore.
const std::map<std::string, std::string> kChoices = {
    {"fresnel", "exact"},          {"specular", "blinn_phong"}, {"foam", "shore"},
    {"reflection", "sky_cubemap"}, {"waves", "gerstner"},       {"shore", "soft"},
    {"precision", "full"},         {"caustics", "area_ratio"}};

// What an engine does: load the variant's files, set the frame's values, pack, draw.
EngineDraw draw(const ShaderBuild& b, const BuildVariant& v, const std::string& lang,
                const SyntheticScene& scene, VkPipelineCache cache) {
    return engine_draw(b, v, lang, scene.uniforms, scene.textures, kSize, cache);
}

} // namespace

TEST_CASE("a variant drawn through the runtime library matches watergen render exactly") {
    const ShaderBuild b = test::open_example_build(false);
    const Selection s = b.select("", kChoices);
    INFO(s.error);
    REQUIRE(s.ok());
    const BuildVariant& v = *s.variant;

    const Preset* preset = find_preset("tropical_ocean");
    REQUIRE(preset);
    Variant variant = default_variant();
    for (const auto& [axis, choice] : v.choices)
        REQUIRE_FALSE(set_choice(variant, axis, choice));
    const VariantBuild reference = build_variant(variant, preset);
    REQUIRE(reference.ok());
    const SyntheticScene scene = preset_scene(kSize, kSize, preset);

    for (size_t i = 0; i < 2; ++i) {
        const LanguageBuild& lang = reference.languages[i];
        const std::string name = to_string(lang.language);
        INFO(name);
        const RenderJob job = make_render_job(lang, scene, {kSize, kSize, 0, false, false});
        // The build's SPIR-V is the one watergen render compiles in-process.
        std::string error;
        CHECK(*b.spirv(v, name, ShaderStage::Fragment, &error) == job.fragment_spirv);
        test::shared_runner().clear_validation_messages();
        const RenderResult expected = test::shared_runner().render(job);
        INFO(expected.error);
        REQUIRE(expected.ok);
        CHECK(test::shared_runner().validation_messages().empty());

        const EngineDraw got = draw(b, v, name, scene, VK_NULL_HANDLE);
        // Every byte the reflected members cover equals the runner's packing.
        CHECK(got.uniforms.size() >= job.uniforms.size());
        const double diff = max_abs_difference(got.rgba, expected.rgba);
        WARN(name << " path: runtime library vs watergen render, " << kSize << "x" << kSize
                  << ", max abs " << diff);
        CHECK(diff == 0.0);
        // Not a blank image: the water shows.
        float lo = got.rgba[0], hi = got.rgba[0];
        for (float f : got.rgba) {
            lo = std::min(lo, f);
            hi = std::max(hi, f);
        }
        CHECK(hi - lo > 0.1f);
    }
    CHECK(engine_gpu().validation_messages().empty());
}

TEST_CASE("the pipeline cache file is written by one run and accepted by the next") {
    const ShaderBuild b = test::open_example_build(false);
    const Selection s = b.select("", kChoices);
    REQUIRE(s.ok());
    test::TempDir dir("engine-cache");
    const auto file = dir.path / "pipelines.bin";
    const SyntheticScene scene = preset_scene(kSize, kSize, find_preset("tropical_ocean"));
    std::string error;

    auto first = load_pipeline_cache(engine_gpu().physical(), engine_gpu().device(), file, &error);
    REQUIRE(first);
    CHECK_FALSE(first->loaded);
    CHECK_THAT(first->note, Catch::Contains("no cache file yet"));
    const EngineDraw a = draw(b, *s.variant, "glsl", scene, first->cache);
    REQUIRE(save_pipeline_cache(engine_gpu().device(), first->cache, file, &error));
    vkDestroyPipelineCache(engine_gpu().device(), first->cache, nullptr);
    CHECK(std::filesystem::file_size(file) >= sizeof(VkPipelineCacheHeaderVersionOne));

    auto second = load_pipeline_cache(engine_gpu().physical(), engine_gpu().device(), file, &error);
    REQUIRE(second);
    CHECK(second->loaded);
    const EngineDraw c = draw(b, *s.variant, "glsl", scene, second->cache);
    vkDestroyPipelineCache(engine_gpu().device(), second->cache, nullptr);
    CHECK(max_abs_difference(a.rgba, c.rgba) == 0.0);

    // A file from elsewhere (here: garbage) starts an empty cache rather than failing.
    std::ofstream(file, std::ios::binary | std::ios::trunc) << std::string(64, 'x');
    auto third = load_pipeline_cache(engine_gpu().physical(), engine_gpu().device(), file, &error);
    REQUIRE(third);
    CHECK_FALSE(third->loaded);
    CHECK_THAT(third->note, Catch::Contains("another device or driver"));
    vkDestroyPipelineCache(engine_gpu().device(), third->cache, nullptr);
    CHECK(engine_gpu().validation_messages().empty());
}
