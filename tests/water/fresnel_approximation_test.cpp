// How far the cheap Fresnel forms are from the exact one (water-models.md), on the CPU.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "optics_support.h"
#include "watergen/water/nodes.h"

using namespace watergen;

namespace {

struct WorstError {
    double error = 0, at_c = 0;
};

// Largest |node(c) - exact(c)| over c in [0, 1] on a 2e5-step grid, in double.
WorstError worst_against_exact(const std::string& node) {
    std::vector<double> cs;
    const int n = 200000;
    for (int i = 0; i <= n; ++i)
        cs.push_back(static_cast<double>(i) / n);
    const auto approx = test::eval_catalog_node(node, cs);
    const auto exact = test::eval_catalog_node("fresnel.exact", cs);
    WorstError w;
    for (size_t i = 0; i < cs.size(); ++i)
        if (std::fabs(approx[i] - exact[i]) > w.error) w = {std::fabs(approx[i] - exact[i]), cs[i]};
    std::printf("%s vs exact: max error %.9f at c = %.6f (%.2f degrees)\n", node.c_str(), w.error,
                w.at_c, std::acos(w.at_c) * 180.0 / M_PI);
    return w;
}

} // namespace

// water-models.md: Schlick "about 0.059 near 83.8 degrees". Measured 0.0590970 at c = 0.10776
// (83.81 degrees); the tolerance covers the grid (2e5 steps) and nothing else.
TEST_CASE("schlick_max_error_against_exact_is_the_measured_0_0591", "[fresnel][golden]") {
    const WorstError w = worst_against_exact("fresnel.schlick");
    CHECK(w.error == Approx(0.059097002).margin(1e-8));
    CHECK(w.at_c == Approx(0.10776).margin(2e-5));
    CHECK(w.error == Approx(0.059).margin(1e-3));
}

// water-models.md: power form (002, q = 4.5) "about 0.084". Measured 0.0838771 at c = 0.119205
// (83.15 degrees).
TEST_CASE("power_max_error_against_exact_is_the_measured_0_084", "[fresnel][golden]") {
    const WorstError w = worst_against_exact("fresnel.power");
    CHECK(w.error == Approx(0.083877102).margin(1e-8));
    CHECK(w.at_c == Approx(0.119205).margin(2e-5));
    CHECK(w.error == Approx(0.084).margin(1e-3));
}

// 002: F = (1 - c)^q, q = 4.5.
TEST_CASE("power_fresnel_matches_002_formula", "[fresnel][golden]") {
    const auto r = test::eval_catalog_node("fresnel.power", {0.0, 0.1, 0.5, 0.9, 1.0});
    CHECK(r[0] == 1.0);
    CHECK(r[1] == Approx(std::pow(0.9, 4.5)).epsilon(1e-12));
    CHECK(r[2] == Approx(std::pow(0.5, 4.5)).epsilon(1e-12));
    CHECK(r[3] == Approx(std::pow(0.1, 4.5)).epsilon(1e-12));
    CHECK(r[4] == 0.0); // pow(0, 4.5): base 0 with a positive exponent is 0 everywhere
}
