// The runtime library's view of a build's companion caustics pass: a variant's reference (the
// draw), the pass opened with its uniform block and the scene's values, its files, and the
// errors of a malformed manifest or pass.json (file and JSON key).
#include <catch2/catch.hpp>

#include <fstream>

#include "engine_builds.h"
#include "watergen/runtime/uniform_writer.h"

using namespace watergen;

namespace {

const BuildVariant& variant(const ShaderBuild& b, const std::string& caustics) {
    const Selection s = b.select("", {{"caustics", caustics}});
    INFO(s.error);
    REQUIRE(s.ok());
    return *s.variant;
}

// A copy of the caustics build, to break.
std::filesystem::path copied(const test::TempDir& dir) {
    const auto out = dir.path / "copy";
    std::filesystem::copy(test::caustics_build(), out, std::filesystem::copy_options::recursive);
    return out;
}

// A copy of the caustics build with `from` replaced by `to` in one file.
std::filesystem::path edited_copy(const test::TempDir& dir, const std::string& file,
                                  const std::string& from, const std::string& to) {
    const auto out = copied(dir);
    std::string text = test::read_file(out / file);
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
    std::ofstream(out / file, std::ios::binary | std::ios::trunc) << text;
    return out;
}

} // namespace

TEST_CASE("a variant with caustics gives its pass: files, uniform block, draw") {
    std::string error;
    const auto b = ShaderBuild::open(test::caustics_build(), &error);
    INFO(error);
    REQUIRE(b);
    CHECK(variant(*b, "none").passes.empty());
    CHECK_FALSE(b->pass(variant(*b, "none"), "caustics", &error));
    CHECK_THAT(error, Catch::Contains("has no caustics pass"));

    const BuildVariant& area = variant(*b, "area_ratio");
    const auto p = b->pass(area, "caustics", &error);
    INFO(error);
    REQUIRE(p);
    CHECK(p->reference.method == "area_ratio");
    CHECK(p->reference.directory == "passes/caustics-area_ratio-gerstner");
    CHECK(p->reference.draw.primitive == "triangles");
    CHECK(p->reference.draw.cells_per_texel == 2);
    CHECK(p->reference.draw.texels == 64);
    CHECK(p->reference.draw.margin_parameter == "caustics_depth");
    CHECK(p->shader.block_name == "WaterParams");
    // Its files through the library: SPIR-V of both paths, the GLSL source, the reflection.
    for (const char* lang : {"glsl", "hlsl"})
        for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
            const auto words = b->spirv(p->shader, lang, stage, &error);
            INFO(lang << " " << error);
            REQUIRE(words);
            CHECK((*words)[0] == 0x07230203u);
            CHECK(b->reflection(p->shader, lang, stage, &error));
        }
    const auto source = b->source(p->shader, "glsl", ShaderStage::Vertex, &error);
    REQUIRE(source);
    CHECK_THAT(*source, Catch::Contains("caustics.area_ratio.gerstner"));
    // The pass's parameters take the writer's checks like a variant's.
    UniformWriter w(p->shader);
    CHECK(w.set("caustics_depth", 3.0f).ok);
    CHECK_FALSE(w.set("caustics_depth", {1.0f, 2.0f}).ok);
    CHECK_FALSE(w.set("shore_hardness", 1.0f).ok);

    const auto photons = b->pass(variant(*b, "photon_splat"), "caustics", &error);
    REQUIRE(photons);
    CHECK(photons->reference.draw.primitive == "points");
    CHECK(photons->reference.draw.photon_share_parameter == "caustics_photon_share");
    CHECK(photons->reference.directory == "passes/caustics-photon_splat-gerstner");
}

TEST_CASE("a malformed pass entry or pass.json is an error naming the file and the key") {
    std::string error;
    {
        test::TempDir dir("engine-pass-primitive");
        const auto out = edited_copy(dir, "manifest.json", "\"primitive\": \"triangles\"",
                                     "\"primitive\": \"lines\"");
        CHECK_FALSE(ShaderBuild::open(out, &error));
        CHECK_THAT(error, Catch::Contains("manifest.json: variants[0].passes.caustics.draw."
                                          "primitive: 'lines'; expected \"triangles\" or "
                                          "\"points\""));
    }
    {
        test::TempDir dir("engine-pass-texels");
        const auto out =
            edited_copy(dir, "manifest.json", "\"texels\": 64", "\"texels\": \"many\"");
        CHECK_FALSE(ShaderBuild::open(out, &error));
        CHECK_THAT(error, Catch::Contains("passes.caustics.draw.texels: expected an unsigned "
                                          "integer"));
    }
    {
        test::TempDir dir("engine-pass-offset");
        const auto out = edited_copy(dir, "passes/caustics-area_ratio-gerstner/pass.json",
                                     "\"offset\": 0", "\"offset\": -4");
        const auto b = ShaderBuild::open(out, &error);
        REQUIRE(b);
        CHECK_FALSE(b->pass(variant(*b, "area_ratio"), "caustics", &error));
        CHECK_THAT(error, Catch::Contains("caustics-area_ratio-gerstner/pass.json: "
                                          "uniform_block.members[0].offset: expected an "
                                          "unsigned integer"));
    }
    {
        test::TempDir dir("engine-pass-missing");
        const auto out = copied(dir);
        std::filesystem::remove(out / "passes/caustics-area_ratio-gerstner/pass.json");
        const auto b = ShaderBuild::open(out, &error);
        REQUIRE(b);
        CHECK_FALSE(b->pass(variant(*b, "area_ratio"), "caustics", &error));
        CHECK_THAT(error, Catch::Contains("caustics-area_ratio-gerstner/pass.json: no such file"));
    }
}

TEST_CASE("the pass grid covers the window and its margin") {
    PassDraw d;
    d.primitive = "triangles";
    d.cells_per_texel = 2;
    d.margin_scale = 1.2;
    d.margin_add = 1.0;
    d.texels = 64;
    std::string error;
    const double window[3] = {-5, -5, 10};
    const auto g = pass_grid(d, window, 3.0, &error);
    REQUIRE(g);
    // Margin 4.6 m = 29.44 texels of 0.15625 m: 30 texels; (64 + 60) x 2 = 248 cells.
    CHECK(g->vertices.size() == 2u * 249 * 249);
    CHECK(g->indices.size() == 6u * 248 * 248);
    // The vertices are in the frame around the window's corner: its centre is (-4.5, -4.5)
    // (host_values.h).
    const double centre = -4.5;
    CHECK(g->vertices[0] == Approx(-5 - 30 * 0.15625 - centre));
    CHECK(g->vertices.back() == Approx(5 + 30 * 0.15625 - centre));
    d.primitive = "points";
    d.photon_share_parameter = "caustics_photon_share";
    const auto p = pass_grid(d, window, 0.0, &error);
    REQUIRE(p);
    // Margin 1 m: 7 texels; (64 + 14) x 2 = 156 cells, a point at each centre.
    CHECK(p->indices.size() == 156u * 156);
    CHECK(p->vertices[0] == Approx(-5 - 7 * 0.15625 + 0.15625 / 4 - centre));
    CHECK(p->values.at("caustics_photon_share") == std::vector<float>{0.25f});
    const double flat[3] = {-5, -5, 0};
    CHECK_FALSE(pass_grid(d, flat, 3.0, &error));
    CHECK_THAT(error, Catch::Contains("(x0, z0, size) with a finite size > 0"));
    CHECK_FALSE(pass_grid(d, window, -10.0, &error));
    CHECK_THAT(error, Catch::Contains("margin"));
}
