// Every catalog node in strict half (16-bit arithmetic) on lavapipe over the stress ranges of
// water-models.md ("Stress ranges every node must survive"): each input takes values from the
// set its name stands for, combined at random (a fixed generator). A tuple whose 16-bit GPU
// result is NaN or Inf where the CPU float result is finite is a node that breaks in half
// precision; there must be none. Run this binary to print the table.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "shared_runner.h"
#include "stress_tuples.h"
#include "watergen/eval/probe/probe.h"
#include "watergen/eval/probe/probe_table.h"
#include "watergen/water/node_catalog.h"

using namespace watergen;
using namespace watergen::test;

namespace {

using Values = std::vector<std::vector<double>>; // each entry one value of the input

const double kInf = INFINITY;

// water-models.md's sets, by what an input is.
const Values kCosines = {{-1},  {-1e-7},       {0}, {1e-7},       {1e-3},
                         {0.5}, {1 - 0x1p-24}, {1}, {1 + 0x1p-23}};
const Values kDistances = {{-1e-3}, {0},   {1e-6}, {0.1},  {10},  {21.1},
                           {190},   {1e3}, {1e4},  {1e30}, {kInf}};
const Values kUnit = {{0}, {1e-6}, {0.3}, {0.5}, {1}};
// Eye rays with y in {0, +-1e-7, +-1e-3} and ordinary ones, unnormalised as given.
const Values kRays = {{1, 0, 0},         {0.6, 1e-7, 0.8}, {0.6, -1e-7, 0.8}, {0.6, 1e-3, 0.8},
                      {0.6, -1e-3, 0.8}, {0, -1, 0},       {0.3, -0.5, 0.81}, {0, 1, 0}};
// Unit normals, tilted ones, and a normal-map texel that decodes to zero.
const Values kNormals = {{0, 1, 0}, {0.6, 0.8, 0}, {0, 0.8, -0.6}, {0, 0, 0}, {1, 0, 0}};
// The sun at the zenith and at the horizon (and just above it).
const Values kSuns = {{0, -1, 0}, {1, 0, 0}, {0.8, -1e-7, 0.6}, {0.6, -0.8, 0}};
// Positions up to 1e5 m, times up to a day.
const Values kPositions3 = {{0, 0, 0}, {12.5, -0.4, -3}, {1e5, 0.5, -1e5}, {-1e5, 2, 1e5}};
const Values kPositions2 = {{0, 0}, {12.5, -3}, {1e5, -1e5}, {-99999.5, 1e5}};
const Values kEyes = {{0, 2, 0}, {1e5, 10, -1e5}, {3, 0.05, -2}};
const Values kTimes = {{0}, {1}, {3600.5}, {86400}};
const Values kLevels = {{0}, {-1}, {1e3}};
const Values kUvs = {{0, 0}, {0.5, 0.5}, {1, 1}, {0.999, 0.001}};
const Values kSlopes = {{0, 0}, {1, -1}, {1e3, 1e3}, {-1e-7, 1e-7}};
const Values kColors = {{0, 0, 0}, {0.5, 0.25, 0.125}, {1, 1, 1}, {10, 2, 0.5}};
const Values kCoefs = {{0.5, 0.1, -0.2, 0.05}, {0, 0, 0, 0}, {1, -1, 1, -1}, {0.25, 0, 0, 0}};

// The stress set of an input, by its name (every catalog input has one).
const Values* stress_set(const std::string& name) {
    static const std::map<std::string, const Values*> sets = {
        {"c", &kCosines},
        {"fresnel", &kUnit},
        {"depth", &kDistances},
        {"path", &kDistances},
        {"height", &kDistances},
        {"refraction", &kColors},
        {"color", &kColors},
        {"pattern", &kUnit},
        {"normal", &kNormals},
        {"base", &kNormals},
        {"to_eye", &kRays},
        {"view_ray", &kRays},
        {"ray", &kRays},
        {"sun_direction", &kSuns},
        {"eye", &kEyes},
        {"level", &kLevels},
        {"time", &kTimes},
        {"xz", &kPositions2},
        {"position", &kPositions3},
        {"surface_point", &kPositions3},
        {"uv", &kUvs},
        {"slope", &kSlopes},
        {"coefs1", &kCoefs},
        {"coefs2", &kCoefs},
    };
    const auto it = sets.find(name);
    return it == sets.end() ? nullptr : it->second;
}

} // namespace

TEST_CASE("every_node_in_strict_half_survives_the_stress_ranges", "[probe][half][stress]") {
    std::printf("%-36s %4s %6s %8s %9s %10s\n", "node", "lang", "tuples", "gpu n-f", "gpu-only",
                "half-only");
    for (const auto& node : node_catalog()) {
        const Graph g = probe_graph(node);
        const ProbeLayout layout = probe_layout(g);
        for (const auto& field : layout.inputs) {
            INFO(node.name << " input " << field.name);
            REQUIRE(stress_set(field.name) != nullptr);
            for (const auto& v : *stress_set(field.name))
                REQUIRE(v.size() == static_cast<size_t>(component_count(field.type)));
        }
        Lcg rng{name_seed(node.name)};
        std::vector<double> in;
        for (size_t t = 0; t < kTuplesPerNode; ++t)
            for (const auto& field : layout.inputs) {
                const Values& set = *stress_set(field.name);
                const auto& v = set[rng.next(static_cast<uint32_t>(set.size()))];
                in.insert(in.end(), v.begin(), v.end());
            }
        for (Language lang : {Language::Glsl, Language::Hlsl}) {
            INFO(node.name << " " << to_string(lang));
            const ProbeRun run =
                checked_probe(g, lang, in, {}, probe_scene_textures(), EmitOptions{true});
            const ProbeSummary s = summarize_probe(run);
            const BrokenTuples half_only = gpu_breaks_where_float_holds(run, in, false);
            std::printf("%-36s %s %6zu %8zu %9zu %10zu\n", node.name.c_str(), to_string(lang),
                        run.tuples, s.gpu.non_finite(), s.gpu_only_non_finite, half_only.count);
            if (half_only.count > 0)
                std::printf("    first half-only non-finite:%s\n",
                            describe_tuple(run, in, half_only.first).c_str());
            CHECK(s.gpu_only_non_finite == 0);
            CHECK(half_only.count == 0);
        }
    }
}
