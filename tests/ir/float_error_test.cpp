#include <catch2/catch.hpp>

#include <cmath>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/float_error.h"

using namespace watergen;

namespace {

double f32(double v) {
    return static_cast<double>(static_cast<float>(v));
}

} // namespace

// (a a - 0.01) 1e8 with a = 0.1: a cancellation whose float result is all rounding. The
// attribution rounds the operations to binary32 one after another, in evaluation order; each
// change is what one more rounding adds, computed here by hand in the same order.
TEST_CASE("attribution_measures_each_rounding_in_evaluation_order", "[evaluator][float_error]") {
    Graph g;
    Expr a = uniform(g, {.name = "a", .type = Type::Float, .default_value = {0.1}, .max = 1.0});
    Expr out = (a * a - 0.01) * 1e8;
    g.set_output("out", out.id());
    const std::vector<EvalSite> sites = evaluation_sites(g, "out", {});
    REQUIRE(sites.size() == 6);
    CHECK(sites[0].op == Op::Uniform);
    CHECK(sites[1].op == Op::Mul);
    CHECK(sites[1].operands == "a, a");
    CHECK(sites[3].op == Op::Sub);

    const PixelAttribution r = attribute_float_error(g, "out", {}, 2, 2, 1, 1, 6);
    REQUIRE(r.ok());
    const double d = (0.1 * 0.1 - 0.01) * 1e8;
    const double af = f32(0.1), pf = f32(af * af), cf = f32(0.01);
    // After each prefix of roundings: a; a a; 0.01; the difference; 1e8 (exact); the product.
    const double steps[6] = {(af * af - 0.01) * 1e8, (pf - 0.01) * 1e8,  (pf - cf) * 1e8,
                             f32(pf - cf) * 1e8,     f32(pf - cf) * 1e8, f32(f32(pf - cf) * 1e8)};
    CHECK(r.double_value[0] == Approx(d).epsilon(1e-12));
    CHECK(r.float_value[0] == steps[5]); // the float evaluation rounds every one of them
    std::map<size_t, double> expected;
    double before = d;
    for (size_t s = 0; s < 6; ++s) {
        if (steps[s] != before) expected[s] = std::fabs(steps[s] - before);
        before = steps[s];
    }
    REQUIRE(r.effects.size() == expected.size());
    for (size_t i = 0; i < r.effects.size(); ++i) {
        INFO("site " << r.effects[i].site);
        REQUIRE(expected.count(r.effects[i].site) == 1);
        CHECK(r.effects[i].change == Approx(expected[r.effects[i].site]).epsilon(1e-9));
        if (i > 0) CHECK(r.effects[i].change <= r.effects[i - 1].change); // largest first
    }
    CHECK(r.effects.front().what.origin == sites[r.effects.front().site].origin);
}

// The spread moves only what two float evaluations can compute differently: parameters and
// constants are the same binary32 values on both sides, and sums, differences, min and abs of
// them round alike, so they spread by nothing; an interpolated varying and a product do, by at
// most one binary32 ulp each (2^-23 relative).
TEST_CASE("float_error_spread_moves_products_and_varyings_only", "[evaluator][float_error]") {
    Graph g;
    Expr a = uniform(g, {.name = "a", .type = Type::Float, .default_value = {0.37}, .max = 1.0});
    Expr u = varying(g, "v_uv", Type::Vec2).x();
    g.set_output("sum", (a + 0.3 - 0.1 + min(a, 0.2) + abs(a)).id());
    g.set_output("product", (u * 3.7).id());
    const uint32_t w = 8, h = 4;
    for (const char* out : {"sum", "product"}) {
        INFO(out);
        const EvalResult d = evaluate_image(g, out, {}, w, h, EvalPrecision::Double);
        REQUIRE(d.ok());
        EvalInputs one, two;
        one.threads = 1;
        two.threads = 2;
        const ErrorSpread s1 = float_error_spread(g, out, one, w, h, d, 4, 0x1p-23);
        const ErrorSpread s2 = float_error_spread(g, out, two, w, h, d, 4, 0x1p-23);
        REQUIRE(s1.ok());
        CHECK(s1.per_pixel == s2.per_pixel); // seeded by lane: threads do not matter
        for (size_t p = 0; p < s1.per_pixel.size(); ++p) {
            if (std::string(out) == "sum") {
                CHECK(s1.per_pixel[p] == 0.0f);
            } else {
                // (1 + e1)(1 + e2) - 1 for the varying's and the product's moves, |e| <= 2^-23.
                CHECK(s1.per_pixel[p] > 0.0f);
                CHECK(s1.per_pixel[p] <= std::fabs(d.values[p]) * 0x1p-22 * (1 + 1e-6));
            }
        }
    }
}
