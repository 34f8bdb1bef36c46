// A build's caustics pass drawn as an engine would (the build directory opened with
// ShaderBuild, the pass's SPIR-V and reflection from its files, the uniforms packed by
// UniformWriter, the grid from pass_grid() and the manifest's draw, additive blending into a
// cleared float target on the test runner) gives the texture render_caustics() draws from the
// same pass built in-process with the same values: max abs 0 (stated tolerance 1e-6) through
// both language paths, for both methods.
#include <catch2/catch.hpp>

#include <algorithm>

#include "engine_builds.h"
#include "shared_runner.h"
#include "watergen/pipeline/caustics_pass_build.h"
#include "watergen/render/caustics_render.h"
#include "watergen/runtime/uniform_writer.h"

using namespace watergen;

namespace {

// Gerstner waves a little steeper than the default, a low sun, a 3 m bottom.
const std::map<std::string, std::vector<double>> kValues = {
    {"time", {1.5}},
    {"sun_direction", {0.25, -0.875, 0.375}},
    {"caustics_window", {-5, -5, 10}},
    {"caustics_depth", {3}},
    {"gerstner_amplitude", {0.25}}};

std::vector<float> floats(const std::vector<double>& v) {
    return std::vector<float>(v.begin(), v.end());
}

// The r channel of the pass drawn through the library, one language path.
std::vector<double> engine_draw(const ShaderBuild& b, const BuildPass& p, const std::string& lang) {
    std::string error;
    const auto vs = b.spirv(p.shader, lang, ShaderStage::Vertex, &error);
    const auto fs = b.spirv(p.shader, lang, ShaderStage::Fragment, &error);
    const auto vr = b.reflection(p.shader, lang, ShaderStage::Vertex, &error);
    const auto fr = b.reflection(p.shader, lang, ShaderStage::Fragment, &error);
    INFO(error);
    REQUIRE((vs && fs && vr && fr));
    const PassDraw& d = p.reference.draw;
    const auto grid =
        pass_grid(d, kValues.at(d.window_parameter), kValues.at(d.margin_parameter)[0], &error);
    REQUIRE(grid);
    UniformWriter w(p.shader);
    for (const auto& [name, v] : kValues)
        REQUIRE(w.set(name, floats(v)).ok);
    for (const auto& [name, v] : grid->values)
        REQUIRE(w.set(name, v).ok);
    const auto bytes = w.pack(*vr, &error); // the one block is the vertex stage's
    REQUIRE(bytes);
    RenderJob job;
    job.vertex_spirv = *vs;
    job.fragment_spirv = *fs;
    job.vertex_reflection = *vr;
    job.fragment_reflection = *fr;
    job.width = job.height = grid->texels;
    job.uniforms = *bytes;
    job.timed_draws = 0;
    job.mesh.vertices = grid->vertices;
    job.mesh.attribute_sizes = {2};
    job.mesh.indices = grid->indices;
    job.mesh.points = grid->points;
    REQUIRE(d.blend == "additive");
    job.additive_blend = true;
    const RenderResult r = test::shared_runner().render(job);
    INFO(r.error);
    REQUIRE(r.ok);
    std::vector<double> intensity;
    for (size_t i = 0; i < r.rgba.size(); i += 4)
        intensity.push_back(r.rgba[i]);
    return intensity;
}

double max_abs(const std::vector<double>& a, const std::vector<double>& b) {
    REQUIRE(a.size() == b.size());
    double m = 0;
    for (size_t i = 0; i < a.size(); ++i)
        m = std::max(m, std::abs(a[i] - b[i]));
    return m;
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
        const Selection s = b->select("", {{"caustics", choice}});
        REQUIRE(s.ok());
        const auto pass = b->pass(*s.variant, "caustics", &error);
        INFO(error);
        REQUIRE(pass);
        const PassDraw& d = pass->reference.draw;

        // The same pass built in-process, drawn by render_caustics with the same values.
        CausticsPassBuild built =
            build_caustics_pass_files(test::caustics_material(), {method, "gerstner"});
        REQUIRE(built.ok());
        const CausticsBuild in_process{built.pass, built.languages, built.diagnostics};
        CausticsRenderSettings settings;
        settings.texels = d.texels;
        settings.cells_per_texel = d.cells_per_texel;
        settings.margin = d.margin_scale * kValues.at("caustics_depth")[0] + d.margin_add;
        const CausticsRender reference = render_caustics(
            test::shared_runner(), in_process, caustics_values(in_process, kValues), settings);
        INFO(reference.error);
        REQUIRE(reference.ok());

        for (size_t lang = 0; lang < 2; ++lang) {
            const std::vector<double> drawn = engine_draw(*b, *pass, lang ? "hlsl" : "glsl");
            REQUIRE(drawn.size() == size_t(d.texels) * d.texels);
            CHECK(max_abs(drawn, reference.intensity[lang]) <= 1e-6);
            // A real caustics texture: light conserved on average, focused into peaks and spread
            // thin between them (measured: mean 1.031 for both methods, max 5.0 (area_ratio's
            // clamp) and 4.89, min 0.73 and 0.60; max abs against render_caustics 0).
            const double mean = mean_intensity(drawn);
            CHECK(mean > 0.9);
            CHECK(mean < 1.1);
            CHECK(*std::max_element(drawn.begin(), drawn.end()) > 1.5);
            CHECK(*std::min_element(drawn.begin(), drawn.end()) < 0.8);
        }
    }
    CHECK(test::shared_runner().validation_messages().empty());
}
