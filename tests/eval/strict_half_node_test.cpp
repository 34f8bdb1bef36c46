// Every catalog node in strict half (16-bit arithmetic, EmitOptions::strict_half) on lavapipe,
// against the CPU evaluator's half mode: on ordinary inputs, how many results agree to the bit
// (binary16 steps); on the extreme finite inputs of node_stress_test, NaN/Inf counts per node.
// Run this binary to print both tables.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <map>

#include "shared_runner.h"
#include "stress_tuples.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/eval/probe/probe_table.h"
#include "watergen/water/node_catalog.h"

using namespace watergen;
using namespace watergen::test;

namespace {

// Nodes whose GLSL strict-half results are not bit-exact with the CPU half model, the largest
// distance measured (binary16 steps) and why. Every other node with a 16-bit output must agree
// to the bit; an entry that agrees to the bit fails the test, so the list stays true.
const std::map<std::string, std::pair<int64_t, std::string>> kKnownHalfGaps = {
    {"extinction.absorb_scatter",
     {11, "exp(-(k s) (d + p)): NIR moves exp's log2(e) factor into the product, "
          "((k log2e) s) (d + p), which rounds differently in binary16"}},
    {"extinction.beer_lambert", {5, "the same rewrite of exp(-a d)"}},
};

// Whether any output of the probe graph is a 16-bit value (the rest are 32-bit islands:
// geometry, whose agreement with the CPU float evaluator node_stress_test checks).
bool has_half_output(const Graph& g) {
    for (const auto& o : g.outputs())
        if (g.node(o.node).relaxed) return true;
    return false;
}

} // namespace

TEST_CASE("every_node_in_strict_half_against_the_cpu_half_model", "[probe][half]") {
    std::printf("%-36s %4s %7s %8s %9s %6s %12s\n", "node", "lang", "values", "equal %", "<=1ulp %",
                "max", "max abs");
    for (const auto& node : node_catalog()) {
        const Graph g = probe_graph(node);
        const std::vector<double> in = ordinary_tuples(probe_layout(g), name_seed(node.name));
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(node.name << " " << to_string(lang));
            const ProbeRun run =
                checked_probe(g, lang, in, {}, probe_scene_textures(), EmitOptions{true});
            const ProbeSummary s = summarize_probe(run);
            const HalfAgreement& a = s.gpu_vs_cpu_half;
            std::printf("%-36s %s %7llu %8.2f %9.2f %6lld %12.3g\n", node.name.c_str(),
                        to_string(lang), static_cast<unsigned long long>(a.values),
                        100.0 * a.equal / std::max<uint64_t>(a.values, 1),
                        100.0 * a.within_1 / std::max<uint64_t>(a.values, 1),
                        static_cast<long long>(a.max_ulps), s.max_gpu_vs_cpu_half);
            if (a.max_ulps > 1)
                std::printf(
                    "    largest gap:%s\n",
                    describe_tuple(run, in, a.max_index / run.layout.output_stride).c_str());
            CHECK(s.gpu_only_non_finite == 0);
            if (lang != Language::Glsl || !has_half_output(g)) continue;
            // glslang's HLSL intrinsics run at 32 bits (strict_half_ops_test): only the GLSL
            // path is the model's arithmetic.
            const auto known = kKnownHalfGaps.find(node.name);
            if (known == kKnownHalfGaps.end()) {
                CHECK(a.max_ulps == 0);
            } else {
                INFO(known->second.second);
                CHECK(a.max_ulps > 0);
                CHECK(a.max_ulps <= known->second.first);
            }
        }
    }
}

TEST_CASE("every_node_in_strict_half_over_extreme_finite_inputs", "[probe][half][stress]") {
    std::printf("%-36s %4s %6s %8s %9s %10s\n", "node", "lang", "tuples", "gpu n-f", "gpu-only",
                "half-only");
    for (const auto& node : node_catalog()) {
        const Graph g = probe_graph(node);
        const std::vector<double> in = stress_tuples(probe_layout(g), name_seed(node.name));
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(node.name << " " << to_string(lang));
            const ProbeRun run =
                checked_probe(g, lang, in, {}, probe_scene_textures(), EmitOptions{true});
            const ProbeSummary s = summarize_probe(run);
            // What half precision costs this node (not a disagreement with the half model).
            const BrokenTuples half_only = gpu_breaks_where_float_holds(run, in, true);
            std::printf("%-36s %s %6zu %8zu %9zu %10zu\n", node.name.c_str(), to_string(lang),
                        run.tuples, s.gpu.non_finite(), s.gpu_only_non_finite, half_only.count);
            if (half_only.count > 0)
                std::printf("    first half-only non-finite:%s\n",
                            describe_tuple(run, in, half_only.first).c_str());
            if (s.gpu_only_non_finite > 0)
                std::printf("    first gpu-only non-finite:%s\n",
                            describe_tuple(run, in, s.first_gpu_only_tuple).c_str());
            // reflection.sky_lookup broke here (dot(N, I) overflowed for a view ray of length
            // 1e4) until its inputs were normalised scale-first (nodes/reflection.cpp).
            CHECK(s.gpu_only_non_finite == 0);
            CHECK(half_only.count == 0);
        }
    }
}
