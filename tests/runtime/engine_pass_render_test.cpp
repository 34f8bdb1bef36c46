// A build's caustics pass drawn by the runtime library as an engine would (the build directory
// opened with ShaderBuild, the pass's SPIR-V and reflection from its files, create_pass_pipeline,
// the uniforms packed by UniformWriter, the grid from pass_grid(), HeadlessDevice::draw_pass into
// the R32_SFLOAT target) gives the texture render_caustics() draws on the test runner from the
// same pass built in-process with the same values: max abs 0 (stated tolerance 1e-6) through
// both language paths, for both methods. And the library's errors: a wrong uniform size, a
// block the pass does not have, a grid that does not fit the draw or the device, a grid too
// large for pass_grid(), a draw description the library cannot draw.
#include <catch2/catch.hpp>

#include <algorithm>

#include "engine_builds.h"
#include "engine_draw_support.h"
#include "shared_runner.h"
#include "watergen/eval/draw/caustics_pass_draw.h"
#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/runtime/pass_pipeline.h"

using namespace watergen;
using namespace watergen::test;

namespace {

// Gerstner waves a little steeper than the default, a low sun, a 3 m bottom.
const std::map<std::string, std::vector<double>> kValues = {
    {"time", {1.5}},
    {"sun_direction", {0.25, -0.875, 0.375}},
    {"caustics_window", {-5, -5, 10}},
    {"caustics_depth", {3}},
    {"gerstner_amplitude", {0.25}}};

BuildPass open_pass(const ShaderBuild& b, const std::string& choice) {
    const Selection s = b.select("", {{"caustics", choice}});
    REQUIRE(s.ok());
    std::string error;
    auto pass = b.pass(*s.variant, "caustics", &error);
    INFO(error);
    REQUIRE(pass);
    return *pass;
}

} // namespace

TEST_CASE("the pass drawn through the runtime library equals render_caustics") {
    std::string error;
    const auto b = ShaderBuild::open(test::caustics_build(), &error);
    INFO(error);
    REQUIRE(b);
    for (const auto& [choice, method] : {std::pair{"area_ratio", CausticsMethod::AreaRatio},
                                         std::pair{"photon_splat", CausticsMethod::PhotonSplat}}) {
        INFO(choice);
        const BuildPass pass = open_pass(*b, choice);
        const PassDraw& d = pass.reference.draw;
        CHECK(d.format == "R32_SFLOAT");

        // The same pass built in-process, drawn by render_caustics with the same values.
        const CausticsPassBuild in_process =
            build_caustics_pass_files(test::caustics_material(), {method, "gerstner"});
        REQUIRE(in_process.ok());
        CausticsRenderSettings settings;
        settings.texels = d.texels;
        settings.cells_per_texel = d.cells_per_texel;
        settings.margin = d.margin_scale * kValues.at("caustics_depth")[0] + d.margin_add;
        const CausticsRender reference = render_caustics(
            test::shared_runner(), in_process, caustics_values(in_process, kValues), settings);
        INFO(reference.error);
        REQUIRE(reference.ok());

        for (size_t lang = 0; lang < 2; ++lang) {
            const EnginePass drawn = engine_pass(*b, pass, lang ? "hlsl" : "glsl", kValues, 5);
            REQUIRE(drawn.intensity.size() == size_t(d.texels) * d.texels);
            CHECK(max_abs_difference(drawn.intensity, reference.intensity[lang]) <= 1e-6);
            // Ready for caustics_map: r = g = b = the intensity, a = 1.
            CHECK(drawn.texture.rgba[1] == drawn.texture.rgba[0]);
            CHECK(drawn.texture.rgba[3] == 1.0f);
            std::vector<double> ms = drawn.draw_ms;
            std::sort(ms.begin(), ms.end());
            WARN(choice << (lang ? " hlsl" : " glsl") << ": draw_pass at " << d.texels
                        << " texels, ms of 5 draws " << ms.front() << " / " << ms[2] << " / "
                        << ms.back() << " (min / median / max)");
            // A real caustics texture: light conserved on average, focused into peaks and spread
            // thin between them (measured: mean 1.031 for both methods, max 5.0 (area_ratio's
            // clamp) and 4.89, min 0.73 and 0.60; max abs against render_caustics 0).
            const double mean = mean_intensity(drawn.intensity);
            CHECK(mean > 0.9);
            CHECK(mean < 1.1);
            CHECK(*std::max_element(drawn.intensity.begin(), drawn.intensity.end()) > 1.5);
            CHECK(*std::min_element(drawn.intensity.begin(), drawn.intensity.end()) < 0.8);
        }
    }
    CHECK(test::shared_runner().validation_messages().empty());
    CHECK(engine_gpu().validation_messages().empty());
}

TEST_CASE("the library's pass draw refuses wrong uniforms and grids that do not fit") {
    std::string error;
    const auto b = ShaderBuild::open(test::caustics_build(), &error);
    REQUIRE(b);
    const BuildPass pass = open_pass(*b, "area_ratio");
    const PassDraw& d = pass.reference.draw;
    HeadlessDevice& gpu = engine_gpu();
    const auto vs = b->spirv(pass.shader, "glsl", ShaderStage::Vertex, &error);
    const auto fs = b->spirv(pass.shader, "glsl", ShaderStage::Fragment, &error);
    const auto vr = b->reflection(pass.shader, "glsl", ShaderStage::Vertex, &error);
    const auto fr = b->reflection(pass.shader, "glsl", ShaderStage::Fragment, &error);
    REQUIRE((vs && fs && vr && fr));
    const VkRenderPass target = gpu.render_pass(VK_FORMAT_R32_SFLOAT, &error);
    REQUIRE(target);
    VariantPipelineDesc desc{&*vs, &*fs, &*vr, &*fr, target, 0, {}, VK_NULL_HANDLE};
    const auto pipeline = create_pass_pipeline(gpu.device(), d, desc, &error);
    REQUIRE(pipeline);
    const auto grid =
        pass_grid(d, kValues.at("caustics_window"), kValues.at("caustics_depth")[0], &error);
    REQUIRE(grid);
    const uint32_t block = vr->bindings.at(0).block_size;

    // Too few bytes, too many, a block the pass does not have, none at all.
    CHECK_FALSE(
        gpu.draw_pass(*pipeline, d, *grid, {{"WaterParams", std::vector<uint8_t>(16)}}, &error));
    CHECK_THAT(error, Catch::Contains("uniform block 'WaterParams' is 16 bytes; the pass's "
                                      "reflection packs it in " +
                                      std::to_string(block)));
    CHECK_FALSE(gpu.draw_pass(*pipeline, d, *grid,
                              {{"WaterParams", std::vector<uint8_t>(block + 64)}}, &error));
    CHECK_THAT(error, Catch::Contains("is " + std::to_string(block + 64) + " bytes"));
    CHECK_FALSE(
        gpu.draw_pass(*pipeline, d, *grid, {{"Params", std::vector<uint8_t>(block)}}, &error));
    CHECK_THAT(error, Catch::Contains("'Params' is not one of the pass's (WaterParams)"));
    CHECK_FALSE(gpu.draw_pass(*pipeline, d, *grid, {}, &error));
    CHECK_THAT(error, Catch::Contains("uniform_buffer 'WaterParams' (set 0, binding 0) is not "
                                      "supplied (" +
                                      std::to_string(block) + " bytes needed)"));

    const std::map<std::string, std::vector<uint8_t>> zeros{
        {"WaterParams", std::vector<uint8_t>(block)}};
    // A grid made for another draw, one whose indices run past its vertices, a target larger than
    // the device draws.
    PassGrid other = *grid;
    other.texels = 128;
    CHECK_FALSE(gpu.draw_pass(*pipeline, d, other, zeros, &error));
    CHECK_THAT(error, Catch::Contains("the grid is for 128 texels; the draw's target has 64"));
    PassGrid broken = *grid;
    broken.indices.back() = uint32_t(broken.vertices.size());
    CHECK_FALSE(gpu.draw_pass(*pipeline, d, broken, zeros, &error));
    CHECK_THAT(error, Catch::Contains("is past its"));
    PassDraw wide = d;
    wide.texels = 1u << 20;
    PassGrid wide_grid = *grid;
    wide_grid.texels = wide.texels;
    CHECK_FALSE(gpu.draw_pass(*pipeline, wide, wide_grid, zeros, &error));
    CHECK_THAT(error, Catch::Contains("a target of 1048576 texels; the device draws 1 to"));
    // pass_grid() itself refuses a grid beyond 2^26 vertices (a 20 km margin here).
    CHECK_FALSE(pass_grid(d, kValues.at("caustics_window"), 20000.0, &error));
    CHECK_THAT(error, Catch::Contains("expected at most 2^26"));

    // A draw description the library cannot draw, and the water's vertex stage for the pass's.
    PassDraw lines = d;
    lines.format = "R8_UNORM";
    CHECK_FALSE(create_pass_pipeline(gpu.device(), lines, desc, &error));
    CHECK_THAT(error, Catch::Contains("draw.format 'R8_UNORM': expected R32_SFLOAT"));
    PassDraw replace = d;
    replace.blend = "replace";
    CHECK_FALSE(create_pass_pipeline(gpu.device(), replace, desc, &error));
    CHECK_THAT(error, Catch::Contains("draw.blend 'replace': expected additive"));
    Reflection no_input = *vr;
    no_input.inputs.clear();
    VariantPipelineDesc water = desc;
    water.vertex_reflection = &no_input;
    CHECK_FALSE(create_pass_pipeline(gpu.device(), d, water, &error));
    CHECK_THAT(error, Catch::Contains("no vec2 input at location 0"));
    CHECK(gpu.validation_messages().empty());
}
