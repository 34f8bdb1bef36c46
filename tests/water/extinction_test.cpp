// Golden values and guards of extinction.linear / exponential / beer_lambert, on the CPU.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "optics_support.h"

using namespace watergen;
using test::eval_catalog_node;

namespace {

// Tuples (depth, path, refraction rgb) for every (depth, path) pair of `set`.
std::vector<double> pairs(const std::vector<double>& set, double refr) {
    std::vector<double> t;
    for (double depth : set)
        for (double path : set)
            t.insert(t.end(), {depth, path, refr, refr, refr});
    return t;
}

const double kSurface[3] = {0.0078, 0.5176, 0.7},
             kDeep[3] = {0.0039, 0.00196, 0.145};      // extinction.linear defaults
const double kExt[3] = {4.5, 75.0, 300.0};             // 000
const double kPureWater[3] = {0.340, 0.0565, 0.00922}; // Pope and Fry 1997

double sat(double x) {
    return std::clamp(x, 0.0, 1.0);
}

} // namespace

// water-models.md: "At depth 10 m the second blend factor is (1, 0.13333, 0.03333)". With
// refraction 0, no path (r1 = 0) and deep colour 1 the output is that factor.
TEST_CASE("linear_depth_blend_factor_at_10_m_is_1_0_13333_0_03333", "[extinction][golden]") {
    const auto r =
        eval_catalog_node("extinction.linear", {10.0, 0.0, 0.0, 0.0, 0.0}, EvalPrecision::Double,
                          {{"extinction_deep_color", {1.0, 1.0, 1.0}}});
    REQUIRE(r.size() == 3);
    CHECK(r[0] == 1.0);
    CHECK(r[1] == Approx(10.0 / 75.0).epsilon(1e-12));
    CHECK(r[2] == Approx(10.0 / 300.0).epsilon(1e-12));
    CHECK(r[1] == Approx(0.13333).margin(5e-6));
    CHECK(r[2] == Approx(0.03333).margin(5e-6));
}

// 000: r1 = mix(refr, surfaceColor, sat(A / visibility)); r2 = mix(r1, depthColor, sat(D / ext)).
TEST_CASE("linear_matches_the_000_formula_in_double", "[extinction][golden]") {
    const std::vector<double> set = {0.0, 0.3, 2.0, 4.0, 10.0, 80.0, 400.0};
    const auto r = eval_catalog_node("extinction.linear", pairs(set, 0.6));
    size_t i = 0;
    for (double depth : set)
        for (double path : set)
            for (int c = 0; c < 3; ++c, ++i) {
                const double r1 = 0.6 + (kSurface[c] - 0.6) * sat(path / 4.0);
                CHECK(r[i] == Approx(r1 + (kDeep[c] - r1) * sat(depth / kExt[c]))
                                  .epsilon(1e-12)
                                  .margin(1e-15));
            }
}

// Guard: sat(path / visibility) with visibility = 0 is 0 / 0 at the shoreline (CPU: sat(NaN) =
// 0, GPU: undefined). Zero visibility is opaque water: the surface colour at any path.
TEST_CASE("linear_zero_visibility_is_opaque_without_dividing_by_zero", "[extinction][guard]") {
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto r = eval_catalog_node("extinction.linear",
                                         {0.0, 0.0, 0.5, 0.5, 0.5, 0.0, 3.0, 0.5, 0.5, 0.5}, p,
                                         {{"extinction_visibility", {0.0}}});
        for (size_t i = 0; i < r.size(); ++i)
            CHECK(r[i] == Approx(kSurface[i % 3]).epsilon(1e-3));
    }
}

// Guard: ext = 0 is water that swallows every channel at once: the deep colour at any depth.
TEST_CASE("linear_zero_extinction_distance_gives_the_deep_colour", "[extinction][guard]") {
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        const auto r = eval_catalog_node("extinction.linear",
                                         {0.0, 0.0, 0.5, 0.5, 0.5, 2.0, 0.0, 0.5, 0.5, 0.5}, p,
                                         {{"extinction_distances", {0.0, 0.0, 0.0}}});
        for (size_t i = 0; i < r.size(); ++i)
            CHECK(r[i] == Approx(kDeep[i % 3]).epsilon(1e-3));
    }
}

// 002: a = exp(-d k); colour = waterColor + a (refr - waterColor), k = 0.5, (0, 0.2, 0.1).
TEST_CASE("exponential_matches_the_002_formula_in_double", "[extinction][golden]") {
    const double water[3] = {0.0, 0.2, 0.1};
    const std::vector<double> set = {0.0, 0.5, 2.0, 7.0, 30.0};
    const auto r = eval_catalog_node("extinction.exponential", pairs(set, 0.7));
    size_t i = 0;
    for (double depth : set)
        for (double path : set)
            for (int c = 0; c < 3; ++c, ++i) {
                (void)depth; // 002's d is the path along the ray; depth plays no part
                CHECK(r[i] ==
                      Approx(water[c] + std::exp(-0.5 * path) * (0.7 - water[c])).epsilon(1e-12));
            }
    // A worked value: path 2 m, refr 0.7: a = e^-1.
    CHECK(r[(0 * set.size() + 2) * 3 + 1] ==
          Approx(0.2 + 0.36787944117144233 * 0.5).epsilon(1e-12));
}

// Pope and Fry 1997: T = exp(-a (depth + path)), colour = refr T.
TEST_CASE("beer_lambert_matches_pure_water_transmittance", "[extinction][golden]") {
    const std::vector<double> set = {0.0, 1.0, 2.0, 5.0, 50.0};
    const auto r = eval_catalog_node("extinction.beer_lambert", pairs(set, 0.8));
    size_t i = 0;
    for (double depth : set)
        for (double path : set)
            for (int c = 0; c < 3; ++c, ++i)
                CHECK(r[i] ==
                      Approx(0.8 * std::exp(-kPureWater[c] * (depth + path))).epsilon(1e-12));
    // depth 2 + path 5 = 7 m of water: red keeps e^-2.38 = 9.3 %, blue 93.7 %.
    CHECK(r[(2 * set.size() + 3) * 3 + 0] == Approx(0.8 * 0.09255058).epsilon(1e-7));
    CHECK(r[(2 * set.size() + 3) * 3 + 2] == Approx(0.8 * 0.93749861).epsilon(1e-7));
}

// Guard: a scene point a hair above the plane gives a negative depth / path. Unclamped,
// exp(+k d) would make the water brighter than what it covers and linear would extrapolate.
TEST_CASE("negative_distances_count_as_no_water", "[extinction][guard]") {
    for (const char* node :
         {"extinction.linear", "extinction.exponential", "extinction.beer_lambert"}) {
        INFO(node);
        const auto r =
            eval_catalog_node(node, {-1e-3, -1e-3, 0.5, 0.5, 0.5, 0.0, 0.0, 0.5, 0.5, 0.5});
        for (int c = 0; c < 3; ++c)
            CHECK(r[c] == r[3 + c]);
    }
    // Also where the linear fades are steps (zero distances): -1e-3 m is the shoreline, not
    // "less than no water".
    const auto r = eval_catalog_node(
        "extinction.linear", {-1e-3, -1e-3, 0.5, 0.5, 0.5, 0.0, 0.0, 0.5, 0.5, 0.5},
        EvalPrecision::Double,
        {{"extinction_distances", {0.0, 0.0, 0.0}}, {"extinction_visibility", {0.0}}});
    for (int c = 0; c < 3; ++c)
        CHECK(r[c] == r[3 + c]);
}

// water-models.md stress ranges: finite and within the convex hull of the colours involved.
TEST_CASE("extinction_nodes_are_finite_and_bounded_at_stress_distances_on_the_cpu",
          "[extinction][stress]") {
    const std::vector<double> set = {-1e-3, 0, 1e-6, 0.1, 10, 21.1, 190, 1e3, 1e4, 1e30, INFINITY};
    const auto tuples = pairs(set, 0.5);
    for (auto p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half})
        for (const std::string node :
             {"extinction.linear", "extinction.exponential", "extinction.beer_lambert"}) {
            INFO(node << " " << to_string(p));
            const auto r = eval_catalog_node(node, tuples, p);
            for (size_t i = 0; i < r.size(); ++i) {
                const int c = static_cast<int>(i % 3);
                double lo = 0.0, hi = 0.5; // beer_lambert: [0, refr]
                if (node == "extinction.linear") {
                    lo = std::min({0.5, kSurface[c], kDeep[c]});
                    hi = std::max({0.5, kSurface[c], kDeep[c]});
                } else if (node == "extinction.exponential") {
                    const double water[3] = {0.0, 0.2, 0.1};
                    lo = std::min(0.5, water[c]);
                    hi = std::max(0.5, water[c]);
                }
                REQUIRE(std::isfinite(r[i]));
                // Half: a mix lands within one binary16 ulp of 0.5 (2^-12) outside the hull.
                const double slack = p == EvalPrecision::Half ? 0x1p-11 : 1e-7;
                CHECK(r[i] >= lo - slack);
                CHECK(r[i] <= hi + slack);
            }
        }
}
