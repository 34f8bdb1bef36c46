// A variant drawn through the engine runtime library (a build directory opened with
// ShaderBuild, uniforms packed by UniformWriter, the pipeline from VariantPipeline, drawn on the
// library's HeadlessGpu) gives the same image as `watergen render` (the variant built in-process
// and drawn by the test runner from make_render_job): max abs 0 through both language paths.
// And the pipeline cache file: written by one run, accepted by the next, same image.
#include <catch2/catch.hpp>

#include <cmath>

#include "engine_builds.h"
#include "shared_runner.h"
#include "watergen/render/variant_render.h"
#include "watergen/runtime/headless_gpu.h"
#include "watergen/runtime/uniform_writer.h"
#include "watergen/water/presets.h"

using namespace watergen;

namespace {

constexpr uint32_t kSize = 96;

// The variant with the most to draw: exact Fresnel, specular, shore foam, sky cube map, Gerstner
// waves (arrays in the block), soft shore.
const std::map<std::string, std::string> kChoices = {
    {"fresnel", "exact"},          {"specular", "blinn_phong"}, {"foam", "shore"},
    {"reflection", "sky_cubemap"}, {"waves", "gerstner"},       {"shore", "soft"},
    {"precision", "full"},         {"caustics", "area_ratio"}};

// `watergen render --preset tropical_ocean`'s scene (flag_checks.cpp preset_scene).
SyntheticScene render_scene(const Preset* preset) {
    SyntheticScene scene = make_synthetic_scene(kSize, kSize);
    for (const auto& [name, values] : preset->values)
        scene.uniforms[name] = values;
    return scene;
}

HeadlessGpu& gpu() {
    static std::unique_ptr<HeadlessGpu> g = [] {
        std::string error;
        auto created = HeadlessGpu::create(&error);
        if (!created) FAIL("no Vulkan device: " << error);
        return created;
    }();
    return *g;
}

struct EngineDraw {
    std::vector<float> rgba;
    std::vector<uint8_t> uniforms;
};

// What an engine does: load the variant's files, set the frame's values, pack, draw.
EngineDraw engine_draw(const ShaderBuild& b, const BuildVariant& v, const std::string& lang,
                       const SyntheticScene& scene, VkPipelineCache cache) {
    std::string error;
    const auto vs = b.spirv(v, lang, ShaderStage::Vertex, &error);
    const auto fs = b.spirv(v, lang, ShaderStage::Fragment, &error);
    const auto vr = b.reflection(v, lang, ShaderStage::Vertex, &error);
    const auto fr = b.reflection(v, lang, ShaderStage::Fragment, &error);
    INFO(error);
    REQUIRE((vs && fs && vr && fr));
    UniformWriter writer(v);
    for (const auto& [name, values] : scene.uniforms) {
        if (!writer.has(name)) continue; // the scene feeds every node; this variant reads fewer
        const std::vector<float> f(values.begin(), values.end());
        const Write w = writer.set(name, f);
        INFO(name << ": " << w.error);
        REQUIRE(w.ok);
    }
    const auto bytes = writer.pack(*fr, &error);
    REQUIRE(bytes);
    VariantPipelineDesc desc{&*vs, &*fs, &*vr, &*fr, gpu().render_pass(), 0, {}, cache};
    auto pipeline = VariantPipeline::create(gpu().device(), desc, &error);
    REQUIRE(pipeline);
    HeadlessDraw draw;
    draw.width = draw.height = kSize;
    draw.uniforms[v.block_name] = *bytes;
    for (const auto& [name, t] : scene.textures)
        draw.textures[name] = HeadlessTexture{t.width, t.height, t.layers, t.rgba};
    EngineDraw out{gpu().draw(*pipeline, draw, &error), *bytes};
    INFO(error);
    REQUIRE(out.rgba.size() == size_t(kSize) * kSize * 4);
    return out;
}

double max_abs(const std::vector<float>& a, const std::vector<float>& b) {
    REQUIRE(a.size() == b.size());
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        REQUIRE(std::isfinite(a[i]));
        m = std::max(m, std::fabs(double(a[i]) - double(b[i])));
    }
    return m;
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
    const SyntheticScene scene = render_scene(preset);

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

        const EngineDraw got = engine_draw(b, v, name, scene, VK_NULL_HANDLE);
        // Every byte the reflected members cover equals the runner's packing.
        CHECK(got.uniforms.size() >= job.uniforms.size());
        const double diff = max_abs(got.rgba, expected.rgba);
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
    CHECK(gpu().messages().empty());
}

TEST_CASE("the pipeline cache file is written by one run and accepted by the next") {
    const ShaderBuild b = test::open_example_build(false);
    const Selection s = b.select("", kChoices);
    REQUIRE(s.ok());
    test::TempDir dir("engine-cache");
    const auto file = dir.path / "pipelines.bin";
    const SyntheticScene scene = render_scene(find_preset("tropical_ocean"));
    std::string error;

    auto first = load_pipeline_cache(gpu().physical(), gpu().device(), file, &error);
    REQUIRE(first);
    CHECK_FALSE(first->loaded);
    CHECK_THAT(first->note, Catch::Contains("no cache file yet"));
    const EngineDraw a = engine_draw(b, *s.variant, "glsl", scene, first->cache);
    REQUIRE(save_pipeline_cache(gpu().device(), first->cache, file, &error));
    vkDestroyPipelineCache(gpu().device(), first->cache, nullptr);
    CHECK(std::filesystem::file_size(file) >= sizeof(VkPipelineCacheHeaderVersionOne));

    auto second = load_pipeline_cache(gpu().physical(), gpu().device(), file, &error);
    REQUIRE(second);
    CHECK(second->loaded);
    const EngineDraw c = engine_draw(b, *s.variant, "glsl", scene, second->cache);
    vkDestroyPipelineCache(gpu().device(), second->cache, nullptr);
    CHECK(max_abs(a.rgba, c.rgba) == 0.0);

    // A file from elsewhere (here: garbage) starts an empty cache rather than failing.
    std::ofstream(file, std::ios::binary | std::ios::trunc) << std::string(64, 'x');
    auto third = load_pipeline_cache(gpu().physical(), gpu().device(), file, &error);
    REQUIRE(third);
    CHECK_FALSE(third->loaded);
    CHECK_THAT(third->note, Catch::Contains("another device or driver"));
    vkDestroyPipelineCache(gpu().device(), third->cache, nullptr);
    CHECK(gpu().messages().empty());
}
