#include <catch2/catch.hpp>

#include <cmath>

#include "shared_runner.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/water/node_catalog.h"

using namespace watergen;

namespace {

ProbeRun probe(const std::string& node, Language lang, const std::vector<double>& inputs,
               const std::map<std::string, std::vector<double>>& uniforms = {}) {
    return test::checked_probe(probe_graph(*find_catalog_node(node)), lang, inputs, uniforms);
}

// water-models.md stress set for c.
const std::vector<double> kStressCosines = {
    -1, -1e-7, 0, 1e-7, 1e-3, 0.5, 1 - std::ldexp(1.0, -24), 1, 1 + std::ldexp(1.0, -23)};

} // namespace

TEST_CASE("fresnel_nodes_are_finite_and_in_unit_range_on_gpu_and_cpu", "[probe][stress]") {
    for (const char* node : {"fresnel.none", "fresnel.schlick", "fresnel.exact"})
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(node << " " << to_string(lang));
            const ProbeRun run = probe(node, lang, kStressCosines);
            for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
                for (double v : *values) {
                    CHECK(std::isfinite(v));
                    CHECK(v >= 0.0);
                    CHECK(v <= 1.0);
                }
            // lavapipe's float math against the CPU's correctly rounded float steps: these
            // nodes use only + - * / sqrt and clamps, so a few ulps of 1.0 bound the gap.
            for (size_t i = 0; i < run.gpu.size(); ++i)
                CHECK(run.gpu[i] == Approx(run.cpu_float[i]).margin(4e-7));
        }
}

TEST_CASE("fresnel_falls_monotonically_from_grazing_to_normal_incidence", "[probe]") {
    std::vector<double> cs;
    for (int i = 0; i <= 1000; ++i)
        cs.push_back(i / 1000.0);
    for (const char* node : {"fresnel.schlick", "fresnel.exact"}) {
        INFO(node);
        const ProbeRun run = probe(node, Language::Glsl, cs);
        for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float})
            for (size_t i = 1; i < values->size(); ++i)
                CHECK((*values)[i] <= (*values)[i - 1]);
    }
}

TEST_CASE("exact_fresnel_reflects_totally_beyond_the_critical_angle_on_the_gpu", "[probe]") {
    // From inside the water: n1 = 1.33333, n2 = 1, critical angle 48.59 degrees.
    const double critical = std::asin(1.0 / 1.33333);
    const std::vector<double> cs = {std::cos(critical + 0.01), std::cos(critical + 0.2), 0.0,
                                    std::cos(critical - 0.01), 1.0};
    const ProbeRun run =
        probe("fresnel.exact", Language::Hlsl, cs, {{"ior_air", {1.33333}}, {"ior_water", {1.0}}});
    CHECK(run.gpu[0] == 1.0);
    CHECK(run.gpu[1] == 1.0);
    CHECK(run.gpu[2] == 1.0);
    CHECK(run.gpu[3] < 1.0);
    CHECK(run.gpu[4] == Approx(0.02040781341207829).epsilon(1e-6)); // same R0 from either side
}

TEST_CASE("absorb_scatter_is_finite_bounded_and_darkens_with_depth", "[probe][stress]") {
    const std::vector<double> set = {-1e-3, 0, 1e-6, 0.1, 10, 21.1, 190, 1e3, 1e4, 1e30, INFINITY};
    std::vector<double> tuples;
    for (double path : set)
        for (double depth : set)
            tuples.insert(tuples.end(), {depth, path, 0.5, 0.5, 0.5});
    for (Language lang : {Language::Glsl, Language::Hlsl}) {
        INFO(to_string(lang));
        const ProbeRun run = probe("extinction.absorb_scatter", lang, tuples);
        REQUIRE(run.layout.output_stride == 3);
        for (const auto* values : {&run.gpu, &run.cpu_double, &run.cpu_float, &run.cpu_half})
            for (double v : *values) {
                CHECK(std::isfinite(v));
                CHECK(v >= -5e-5); // half-precision cancellation, see extinction_golden_test
                CHECK(v <= 0.5 + 1e-6);
            }
        // Only the transmittance depends on depth: deeper is never brighter (per path, per
        // channel).
        for (size_t p = 0; p < set.size(); ++p)
            for (size_t d = 1; d < set.size(); ++d)
                for (int c = 0; c < 3; ++c)
                    CHECK(run.gpu[(p * set.size() + d) * 3 + c] <=
                          run.gpu[(p * set.size() + d - 1) * 3 + c]);
        // exp() on lavapipe is not correctly rounded: relative 2e-6 measured headroom.
        for (size_t i = 0; i < run.gpu.size(); ++i)
            CHECK(run.gpu[i] == Approx(run.cpu_double[i]).epsilon(2e-6).margin(1e-7));
    }
}

TEST_CASE("probes_beyond_one_dispatch_run_in_chunks", "[probe]") {
    // Vulkan guarantees 65535 workgroups of 64 per dispatch; one tuple more than that needs a
    // second dispatch, and every tuple of it must come back in its place.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    g.set_output("value", (x * 2.0 + 1.0).id());
    const size_t n = size_t{65535} * kProbeWorkgroupSize + 37;
    std::vector<double> inputs(n);
    for (size_t i = 0; i < n; ++i)
        inputs[i] = static_cast<double>(i % 4096);
    const ProbeRun run = test::checked_probe(g, Language::Glsl, inputs);
    REQUIRE(run.tuples == n);
    size_t wrong = 0;
    for (size_t i = 0; i < n; ++i)
        wrong += run.gpu[i] != inputs[i] * 2.0 + 1.0;
    CHECK(wrong == 0);
    CHECK(run.gpu[n - 1] == (n - 1) % 4096 * 2.0 + 1.0);
}
