#include <catch2/catch.hpp>

#include <cmath>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"

using namespace watergen;

TEST_CASE("derivatives_difference_within_a_quad", "[evaluator]") {
    Graph g;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Expr f = uv.x() * uv.x() * 100.0 + uv.y() * 10.0;
    g.set_output("dx", ddx(f).id());
    g.set_output("dy", ddy(f).id());
    const auto dx = evaluate_image(g, "dx", {}, 4, 4, EvalPrecision::Double);
    const auto dy = evaluate_image(g, "dy", {}, 4, 4, EvalPrecision::Double);
    REQUIRE(dx.ok());
    // Pixel (0,0) and (1,0): u = 0.125, 0.375 -> d(100 u^2) = 100 (0.375^2 - 0.125^2) = 12.5.
    CHECK(dx.values[0] == Approx(12.5));
    CHECK(dx.values[1] == Approx(12.5));
    CHECK(dx.values[2] == Approx(100 * (0.875 * 0.875 - 0.625 * 0.625)));
    CHECK(dy.values[0] == Approx(2.5)); // 10 * (0.375 - 0.125)
}

TEST_CASE("linear_sampling_follows_the_vulkan_formula", "[evaluator]") {
    // 2x1 texture: red channel 0 and 1. Texel centres at u = 0.25, 0.75; clamp to edge.
    const float texels[8] = {0, 0, 0, 1, 1, 0, 0, 1};
    Graph g;
    Expr uv = varying(g, "uv", Type::Vec2);
    g.set_output("out", sample(texture(g, {"t", Type::Texture2D, "", ""}), uv).x().id());
    EvalInputs in;
    in.textures["t"] = TextureView{2, 1, texels};
    in.varyings["uv"] = {0.25, 0.5, 0.5, 0.5, 0.75, 0.5, 0.0, 0.5, 1.0, 0.5, 0.6, 0.5};
    in.lanes = 6;
    auto r = evaluate(g, "out", in, EvalPrecision::Double);
    REQUIRE(r.ok());
    const std::vector<double> expected = {0.0, 0.5, 1.0, 0.0, 1.0, 0.7};
    for (size_t i = 0; i < expected.size(); ++i)
        CHECK(r.values[i] == Approx(expected[i]).margin(1e-12));
    in.filter = Filter::Nearest;
    r = evaluate(g, "out", in, EvalPrecision::Double);
    CHECK(r.values == std::vector<double>{0.0, 1.0, 1.0, 0.0, 1.0, 1.0});
}

TEST_CASE("missing_texture_is_an_error_not_a_crash", "[evaluator]") {
    Graph g;
    Expr uv = varying(g, "uv", Type::Vec2);
    g.set_output("out", sample(texture(g, {"t", Type::Texture2D, "", ""}), uv).id());
    EvalInputs in;
    in.varyings["uv"] = {0.5, 0.5};
    in.lanes = 1;
    const auto r = evaluate(g, "out", in, EvalPrecision::Float);
    CHECK(r.error == "texture 't' not supplied");
}

TEST_CASE("float_and_half_modes_round_every_intermediate", "[evaluator]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    RelaxedScope relaxed(g, true);
    g.set_output("out", ((x + 1e-4) - x).id());
    EvalInputs in;
    in.varyings["x"] = {1000.0};
    in.lanes = 1;
    CHECK(evaluate(g, "out", in, EvalPrecision::Double).values[0] == Approx(1e-4).epsilon(1e-9));
    // float: 1000.0001 rounds to 1000.0001220703125; half: 1000 + 1e-4 rounds back to 1000.
    CHECK(evaluate(g, "out", in, EvalPrecision::Float).values[0] == 0.0001220703125);
    CHECK(evaluate(g, "out", in, EvalPrecision::Half).values[0] == 0.0);
}

TEST_CASE("results_do_not_depend_on_the_thread_count", "[evaluator]") {
    // 1001 lanes: four blocks of 256 and a partial one, not whole quads at the end.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr k = uniform(g, {.name = "k", .type = Type::Float, .default_value = {0.37}, .max = 1.0});
    Expr shared = sin(k * 3.0) + k * k; // the same on every lane: computed once per thread
    Expr f = sin(x * shared) * exp(-x * k) + ddx(x * x) + ddy(x);
    g.set_output("f", f.id());
    EvalInputs in;
    for (size_t l = 0; l < 1001; ++l)
        in.varyings["x"].push_back(static_cast<double>(l % 37) * 0.25 - 3.0);
    in.lanes = 1001;
    for (EvalPrecision p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
        INFO(to_string(p));
        in.threads = 1;
        const EvalResult one = evaluate(g, "f", in, p);
        in.threads = 3;
        const EvalResult three = evaluate(g, "f", in, p);
        REQUIRE(one.ok());
        REQUIRE(three.ok());
        CHECK(one.values == three.values);
        // Lane 0 by hand (double): x = -3; ddx pairs lanes 0 and 1 (x = -2.75), ddy 0 and 2.
        if (p == EvalPrecision::Double) {
            const double s = std::sin(0.37 * 3.0) + 0.37 * 0.37;
            const double expected =
                std::sin(-3.0 * s) * std::exp(3.0 * 0.37) + (2.75 * 2.75 - 9.0) + (-2.5 + 3.0);
            CHECK(one.values[0] == Approx(expected).epsilon(1e-14));
        }
    }
}

TEST_CASE("derivative_of_an_infinite_parameter_is_nan_on_every_lane", "[evaluator]") {
    // A parameter is the same on every lane, yet its quad difference is inf - inf = NaN, as on
    // the GPU; and 0 for a finite one.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr k = uniform(g, {.name = "k", .type = Type::Float, .default_value = {1.0}, .max = 1.0});
    g.set_output("d", (ddx(k) + x * 0.0).id());
    EvalInputs in;
    in.varyings["x"] = {1, 2, 3, 4};
    in.lanes = 4;
    CHECK(evaluate(g, "d", in, EvalPrecision::Float).values == std::vector<double>(4, 0.0));
    in.uniforms["k"] = {INFINITY};
    for (double v : evaluate(g, "d", in, EvalPrecision::Float).values)
        CHECK(std::isnan(v));
}
