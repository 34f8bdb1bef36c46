// Caustics end to end through the runtime library: a water variant with caustics=area_ratio (the
// example material's build), its caustics pass drawn by HeadlessDevice::draw_pass with the scene's
// values, that texture bound as the variant's caustics_map and the variant drawn by HeadlessDevice,
// gives the test runner's render of the same variant (built in-process, make_render_job, as
// `watergen render` draws it) with the same texture: max abs 0 through both language paths. The
// pass's light shows: the image differs from caustics=none's.
#include <catch2/catch.hpp>

#include "engine_builds.h"
#include "engine_draw_support.h"
#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"

using namespace watergen;
using namespace watergen::test;

namespace {

constexpr uint32_t kSize = 96;

// Gerstner waves, area_ratio caustics, seen through the water (no foam or specular highlight
// over the bottom).
const std::map<std::string, std::string> kChoices = {{"caustics", "area_ratio"},
                                                     {"waves", "gerstner"},
                                                     {"foam", "none"},
                                                     {"specular", "none"},
                                                     {"precision", "full"}};

// The variant with `caustics` in place of its own choice.
const BuildVariant& with_caustics(const ShaderBuild& b, const BuildVariant& v,
                                  const std::string& caustics) {
    std::map<std::string, std::string> choices = v.choices;
    choices["caustics"] = caustics;
    const Selection s = b.select(v.scene, choices);
    INFO(s.error);
    REQUIRE(s.ok());
    return *s.variant;
}

// The runner's image of the variant built in-process, with the scene's textures.
std::vector<float> runner_image(const BuildVariant& v, const SyntheticScene& scene, size_t lang) {
    Variant variant = default_variant();
    for (const auto& [axis, choice] : v.choices)
        REQUIRE_FALSE(set_choice(variant, axis, choice));
    const VariantBuild build = build_variant(variant, find_preset("tropical_ocean"));
    REQUIRE(build.ok());
    const RenderJob job = make_render_job(build.languages[lang], scene, {kSize, kSize, 0});
    const RenderResult r = shared_runner().render(job);
    INFO(r.error);
    REQUIRE(r.ok);
    return r.rgba;
}

} // namespace

TEST_CASE("a caustics variant drawn through the library with its library-drawn pass") {
    const ShaderBuild b = open_example_build(false);
    const Selection s = b.select("", kChoices, Fallback::NearestKept);
    INFO(s.error);
    REQUIRE(s.ok());
    const BuildVariant& v = *s.variant;
    REQUIRE(v.choices.at("caustics") == "area_ratio");
    std::string error;
    const auto pass = b.pass(v, "caustics", &error);
    INFO(error);
    REQUIRE(pass);

    // The scene's values at the depth of its caustics map; the pass starts at its defaults.
    SyntheticScene scene = preset_scene(kSize, kSize, find_preset("tropical_ocean"));
    scene.uniforms["caustics_depth"] = {kSceneCausticsDepth};
    std::map<std::string, std::vector<double>> values;
    for (const BlockParameter& p : pass->shader.parameters)
        values[p.name] = p.default_value;
    for (const auto& [name, value] : scene.uniforms)
        if (values.count(name)) values[name] = value;

    for (size_t lang = 0; lang < 2; ++lang) {
        const std::string name = lang ? "hlsl" : "glsl";
        INFO(name);
        const EnginePass drawn = engine_pass(b, *pass, name, values);
        scene.textures["caustics_map"] = drawn.texture;
        const std::vector<float> expected = runner_image(v, scene, lang);
        const auto& textures = scene.textures;
        const EngineDraw got = engine_draw(b, v, name, scene.uniforms, textures, kSize);
        const double diff = max_abs_difference(got.rgba, expected);
        WARN(name << ": area_ratio variant with the library's pass texture, library vs runner, "
                  << kSize << "x" << kSize << ", max abs " << diff);
        CHECK(diff == 0.0);

        // Without caustics the bottom is lit evenly: the pass's light changes the image.
        const EngineDraw none =
            engine_draw(b, with_caustics(b, v, "none"), name, scene.uniforms, textures, kSize);
        const double lit = max_abs_difference(got.rgba, none.rgba);
        WARN(name << ": area_ratio vs caustics=none, max abs " << lit);
        CHECK(lit > 0.02);
    }
    CHECK(shared_runner().validation_messages().empty());
    CHECK(engine_gpu().validation_messages().empty());
}
