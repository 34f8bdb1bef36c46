#include <catch2/catch.hpp>

#include <cmath>

#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/water/node_catalog.h"
#include "watergen/water/nodes.h"

using namespace watergen;

namespace {
EvalResult absorb_scatter(const std::vector<double>& depth, const std::vector<double>& path,
                          EvalPrecision p) {
    Graph g;
    Expr d = varying(g, "depth", Type::Float);
    Expr a = varying(g, "path", Type::Float);
    Expr refr = constant(g, {0.5, 0.5, 0.5});
    RelaxedScope relaxed(g, true);
    g.set_output("out", extinction_absorb_scatter(g, {d, a, refr}).id());
    EvalInputs in;
    in.lanes = depth.size();
    in.varyings["depth"] = depth;
    in.varyings["path"] = path;
    return evaluate(g, "out", in, p);
}
} // namespace

// water-models.md, 003 tropical set at depth = 2, acc = 5, refr = 0.5, E = 1.
TEST_CASE("absorb_scatter_matches_golden_colour", "[extinction]") {
    const auto r = absorb_scatter({2.0}, {5.0}, EvalPrecision::Double);
    REQUIRE(r.ok());
    REQUIRE(r.components == 3);
    // The document gives 8 significant digits.
    CHECK(r.values[0] == Approx(0.03267854).epsilon(1e-7));
    CHECK(r.values[1] == Approx(0.17479188).epsilon(1e-7));
    CHECK(r.values[2] == Approx(0.23184654).epsilon(1e-7));
    // And against the formula in double at full precision.
    const double k[3] = {0.46, 0.09, 0.06}, scatter[3] = {0.05, 0.05, 0.10};
    const double s = std::exp(-0.11 * 5.0);
    for (int i = 0; i < 3; ++i) {
        const double t = std::exp(-k[i] * 7.0);
        CHECK(r.values[i] == Approx(scatter[i] + (0.5 * t - scatter[i]) * s).epsilon(1e-12));
    }
}

TEST_CASE("absorb_scatter_is_finite_at_stress_depths", "[extinction][stress]") {
    const std::vector<double> set = {-1e-3, 0, 1e-6, 0.1, 10, 21.1, 190, 1e3, 1e4, 1e30, INFINITY};
    std::vector<double> depth, path;
    for (double d : set)
        for (double a : set) {
            depth.push_back(d);
            path.push_back(a);
        }
    // mix(scatter, refr T, S) = scatter + (refr T - scatter) S cancels to 0 when T = 0 and
    // S = 1; rounding may leave a residue of one ulp of the scatter colour (0.05..0.1): 2^-24 *
    // 0.1 in float, 2^-11 * 0.1 in half.
    const std::pair<EvalPrecision, double> modes[] = {
        {EvalPrecision::Double, 0.0}, {EvalPrecision::Float, 1e-8}, {EvalPrecision::Half, 5e-5}};
    for (auto [p, slack] : modes) {
        INFO(to_string(p));
        const auto r = absorb_scatter(depth, path, p);
        REQUIRE(r.ok());
        double lowest = 1.0;
        for (double v : r.values) {
            CHECK(std::isfinite(v));
            lowest = std::min(lowest, v);
            CHECK(v <=
                  0.5 + 1e-3); // never brighter than the refracted colour (-1e-3 m adds < 0.05 %)
        }
        CHECK(lowest >= -slack);
    }
}

TEST_CASE("zero_absorption_over_an_infinite_path_is_finite", "[extinction][stress]") {
    // 0 * inf is NaN: without the distance cap every model returned NaN here.
    const std::map<std::string, std::vector<std::pair<std::string, std::vector<double>>>> zeroed = {
        {"extinction.absorb_scatter",
         {{"absorb_coefficients", {0, 0, 0}}, {"scatter_coefficient", {0}}}},
        {"extinction.beer_lambert", {{"extinction_pure_water_absorption", {0, 0, 0}}}},
        {"extinction.exponential", {{"extinction_density", {0}}}},
    };
    for (const auto& [node, params] : zeroed) {
        INFO(node);
        const Graph g = probe_graph(*find_catalog_node(node));
        EvalInputs in;
        in.lanes = 2;
        in.varyings["depth"] = {INFINITY, 1.0};
        in.varyings["path"] = {INFINITY, INFINITY};
        in.varyings["refraction"] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
        for (const auto& [name, value] : params)
            in.uniforms[name] = value;
        for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
            const auto r = evaluate(g, "value", in, p);
            REQUIRE(r.ok());
            for (double v : r.values)
                CHECK(std::isfinite(v));
        }
    }
}
