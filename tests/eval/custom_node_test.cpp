// examples/custom_node's nodes, compiled into this test as into the example's generator: a
// project's axis (fog) and a project's choice on watergen's fresnel axis join composition,
// rendering and probing with no other code. Rendered on lavapipe through both languages
// against the CPU reference within today's bounds (5e-5 plus each pixel's float bound), and
// probed against the CPU in double and an independent formula.
#include <catch2/catch.hpp>

#include <cmath>

#include "shared_runner.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/water/axis_registry.h"
#include "watergen/water/water_shader.h"

using namespace watergen;

namespace {

Variant lab_variant(std::initializer_list<std::pair<const char*, const char*>> choices) {
    Variant v = default_variant();
    for (const auto& [axis, choice] : choices) {
        INFO(axis << "=" << choice);
        REQUIRE_FALSE(set_choice(v, axis, choice));
    }
    return v;
}

// Over R, G and B of every pixel (compare_images).
double max_abs(const ImageRGBA32F& a, const ImageRGBA32F& b) {
    const ImageErrorStats stats = compare_images(a, b);
    REQUIRE(stats.error.empty());
    return stats.max_abs;
}

VariantRender render(const Variant& v, const SyntheticScene& scene, const RenderSettings& s) {
    const VariantBuild b = build_variant(v);
    INFO(v.key());
    REQUIRE(b.ok());
    VariantRender r = render_variant(test::shared_runner(), b, scene, s);
    INFO(r.error);
    REQUIRE(r.ok());
    return r;
}

} // namespace

TEST_CASE("the_project_axis_is_composed_after_the_shore_and_keyed_last", "[custom_node]") {
    REQUIRE(registration_errors().empty());
    const std::vector<std::string>& order = composition_order();
    const auto shore = std::find(order.begin(), order.end(), "shore");
    REQUIRE(shore != order.end());
    REQUIRE(shore + 1 != order.end());
    CHECK(*(shore + 1) == "fog");
    CHECK(axes().back().name == "fog");
    const std::string key = default_variant().key();
    CHECK(key.substr(key.size() - 9) == ",fog=none");
    const AxisInfo* fresnel = find_axis("fresnel");
    REQUIRE(fresnel);
    CHECK(fresnel->choices.back().name == "spherical_gaussian");
    CHECK(fresnel->choices.back().author.file.find("fresnel_spherical_gaussian.cpp") !=
          std::string::npos);
}

TEST_CASE("the_project_nodes_render_glsl_equal_to_hlsl_and_agree_with_the_cpu", "[render]") {
    // The CPU in float and double with each pixel's float error bound: the agreement below.
    const RenderSettings settings{.width = 64, .height = 64, .timed_draws = 1, .float_bound = true};
    const SyntheticScene scene = make_synthetic_scene(settings.width, settings.height);
    const VariantRender plain = render(lab_variant({{"waves", "gerstner"}}), scene, settings);
    for (const char* fog : {"exponential", "rational"}) {
        const Variant v =
            lab_variant({{"fog", fog}, {"fresnel", "spherical_gaussian"}, {"waves", "gerstner"}});
        INFO(v.key());
        const VariantRender r = render(v, scene, settings);
        CHECK(r.validation_messages.empty());
        CHECK(max_abs(r.gpu_image[0], r.gpu_image[1]) == 0.0);
        for (const Agreement& a : r.agreement) { // the GLSL and the HLSL image
            CHECK(a.holds());
            CHECK(a.tolerance == 5e-5);
            CHECK(a.compared == 64u * 64u);
        }
        // The fog is in the picture: far water and sky fade by far more than any tolerance.
        CHECK(max_abs(r.gpu_image[0], plain.gpu_image[0]) > 0.05);
    }
}

TEST_CASE("the_fog_nodes_probe_as_their_formulas_on_both_paths", "[render]") {
    // color (3), distance: the distances span no fog to full fog at the default density 0.004.
    const std::vector<double> tuples = {0.1, 0.2, 0.3, 0.0,   0.1, 0.2, 0.3, 10.0,
                                        0.9, 0.5, 0.1, 250.0, 0.0, 0.0, 0.0, 1e5};
    const double density = 0.004;
    const double fog[3] = {0.62, 0.70, 0.78};
    for (const char* name : {"fog.exponential", "fog.rational"}) {
        const CatalogNode* node = find_catalog_node(name);
        REQUIRE(node);
        const Graph g = probe_graph(*node);
        REQUIRE_FALSE(has_errors(g.diagnostics()));
        for (Language language : {Language::Glsl, Language::Hlsl}) {
            INFO(name << " " << (language == Language::Glsl ? "glsl" : "hlsl"));
            const ProbeRun run = run_probe(test::shared_runner(), g, language, tuples);
            INFO(run.error);
            REQUIRE(run.ok());
            REQUIRE(run.tuples == 4);
            for (size_t t = 0; t < 4; ++t) {
                const double x = density * tuples[4 * t + 3];
                const double transmittance = std::string(name) == "fog.exponential"
                                                 ? std::exp(-x)
                                                 : 1.0 / (1.0 + x + 0.5 * x * x);
                for (size_t c = 0; c < 3; ++c) {
                    const double want = fog[c] + (tuples[4 * t + c] - fog[c]) * transmittance;
                    const size_t at = t * run.layout.output_stride + c;
                    // Double against the formula: rounding only. GPU float against double:
                    // values within [0, 1] through one exp and one mix, a few float ulps of 1.
                    CHECK(run.cpu_double[at] == Approx(want).margin(1e-12));
                    CHECK(std::fabs(run.gpu[at] - run.cpu_double[at]) < 1e-6);
                }
            }
        }
    }
}
