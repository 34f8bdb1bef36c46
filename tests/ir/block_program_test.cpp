// The compiled CPU evaluator (generator/ir/cpu/block_program.cpp and its kernels): what it computes
// in float storage, lane-invariant arguments, values read in place, and errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"

using namespace watergen;

namespace {

Parameter vector_parameter(const std::string& name, std::vector<double> value) {
    Parameter p;
    p.name = name;
    p.type = float_type(static_cast<int>(value.size()));
    p.default_value = std::move(value);
    p.min = -10;
    p.max = 10;
    return p;
}

uint32_t bits(float f) {
    uint32_t b = 0;
    std::memcpy(&b, &f, 4);
    return b;
}

} // namespace

TEST_CASE("sin_and_cos_in_float_are_the_double_results_rounded", "[evaluator]") {
    // Float storage computes sin and cos of a binary32 argument together, in vectorised double
    // arithmetic, and leaves values near a binary32 rounding boundary to std::sin / std::cos.
    // Every 4099th binary32 bit pattern (all exponents, both signs) and the edges of the fast
    // path must give float(std::sin(double(x))) to the bit.
    std::vector<double> x;
    for (uint64_t b = 0; b < (uint64_t(1) << 32); b += 4099) {
        float f = 0;
        const auto u = static_cast<uint32_t>(b);
        std::memcpy(&f, &u, 4);
        x.push_back(f);
    }
    for (double v :
         {0.0, -0.0, 0x1p19, -0x1p19, 0x1.000002p19, 0x1p-149, 0x1.921fb6p1, 0x1.921fb6p0,
          std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()})
        x.push_back(v);
    Graph g;
    Expr a = varying(g, "x", Type::Float);
    g.set_output("sc", vec2(sin(a), cos(a)).id());
    EvalInputs in;
    in.varyings["x"] = x;
    in.lanes = x.size();
    const EvalResult r = evaluate(g, "sc", in, EvalPrecision::Float);
    REQUIRE(r.ok());
    size_t wrong = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        const float s = static_cast<float>(std::sin(x[i]));
        const float c = static_cast<float>(std::cos(x[i]));
        wrong += bits(static_cast<float>(r.values[2 * i])) != bits(s);
        wrong += bits(static_cast<float>(r.values[2 * i + 1])) != bits(c);
    }
    CHECK(x.size() > 1000000);
    CHECK(wrong == 0);
}

TEST_CASE("min_max_and_clamp_keep_the_evaluators_signed_zero_and_nan_rules", "[evaluator]") {
    // min(a, b) and max(a, b) give a of +0 and -0 and b of two NaNs; clamp(x, lo, hi) is
    // fmin(hi, fmax(lo, x)) in glibc's terms. Golden images were made with these rules.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Graph g;
    Expr a = varying(g, "a", Type::Float), b = varying(g, "b", Type::Float);
    g.set_output("out", vec3(min(a, b), max(a, b), clamp(a, b, b)).id());
    EvalInputs in;
    in.varyings["a"] = {0.0, -0.0, nan, 2.0, -0.0};
    in.varyings["b"] = {-0.0, 0.0, -nan, nan, 0.0};
    in.lanes = 5;
    for (EvalPrecision p : {EvalPrecision::Double, EvalPrecision::Float}) {
        const EvalResult r = evaluate(g, "out", in, p);
        REQUIRE(r.ok());
        CHECK_FALSE(std::signbit(r.values[0])); // min(+0, -0) = +0
        CHECK(std::signbit(r.values[3]));       // min(-0, +0) = -0
        CHECK(std::signbit(r.values[4]));       // max(-0, +0) = -0
        CHECK(std::isnan(r.values[6]));
        CHECK(std::signbit(r.values[6])); // min(NaN, -NaN) = -NaN
        CHECK(r.values[9] == 2.0);        // min(2, NaN) = 2
        CHECK(r.values[10] == 2.0);
        CHECK(std::signbit(r.values[14])); // clamp(-0, +0, +0) = -0
    }
}

TEST_CASE("lane_invariant_arguments_give_what_per_lane_ones_give", "[evaluator]") {
    // The same operations on a parameter (one value for all lanes) and on a varying holding
    // that value on every lane, in every precision, relaxed or not.
    const std::vector<double> value = {0.3, -1.7, 2.5};
    for (bool relaxed : {false, true})
        for (EvalPrecision p : {EvalPrecision::Double, EvalPrecision::Float, EvalPrecision::Half}) {
            Graph g;
            Expr u = uniform(g, vector_parameter("u", value));
            Expr same = varying(g, "same", Type::Vec3), w = varying(g, "w", Type::Vec3);
            RelaxedScope scope(g, relaxed);
            auto shade = [](Expr x, Expr y) {
                Expr d = dot(x, y);
                return vec4(normalize(cross(x, y)) * d + pow(abs(x), y) - mix(x, y, 0.25),
                            min(x.y(), y.z()) / (sin(d) + 2.0));
            };
            g.set_output("uw", shade(u, w).id());
            g.set_output("sw", shade(same, w).id());
            g.set_output("wu", shade(w, u).id());
            g.set_output("ws", shade(w, same).id());
            EvalInputs in;
            in.lanes = 300;
            for (size_t l = 0; l < in.lanes; ++l)
                for (size_t c = 0; c < 3; ++c) {
                    in.varyings["same"].push_back(value[c]);
                    in.varyings["w"].push_back(0.01 * double(l) - 0.7 * double(c));
                }
            const EvalResult uw = evaluate(g, "uw", in, p), sw = evaluate(g, "sw", in, p);
            const EvalResult wu = evaluate(g, "wu", in, p), ws = evaluate(g, "ws", in, p);
            REQUIRE((uw.ok() && sw.ok() && wu.ok() && ws.ok()));
            CHECK(uw.values == sw.values);
            CHECK(wu.values == ws.values);
            CHECK(uw.values[0] != uw.values[4 * 299]);
        }
}

TEST_CASE("a_loop_can_pass_its_carried_values_on_swapped", "[loop]") {
    // next = (b, a + i): the carried values are read in place, so they must not be overwritten
    // while the others are still read.
    Graph g;
    Expr a = varying(g, "a", Type::Float), b = varying(g, "b", Type::Float);
    const auto r = loop(g, 5, {a, b}, [](Expr i, const std::vector<Expr>& c) {
        return LoopStep{{c[1], c[0] + i}, {}};
    });
    g.set_output("out", vec2(r[0], r[1]).id());
    EvalInputs in;
    in.varyings["a"] = {1.0, 10.0};
    in.varyings["b"] = {2.0, 20.0};
    in.lanes = 2;
    const EvalResult res = evaluate(g, "out", in, EvalPrecision::Float);
    REQUIRE(res.ok());
    for (size_t l = 0; l < 2; ++l) {
        double x = in.varyings["a"][l], y = in.varyings["b"][l];
        for (int i = 0; i < 5; ++i) {
            const double t = y;
            y = x + i;
            x = t;
        }
        CHECK(res.values[2 * l] == x);
        CHECK(res.values[2 * l + 1] == y);
    }
}

TEST_CASE("the_first_block_that_cannot_be_evaluated_names_the_error", "[evaluator]") {
    Graph g;
    Expr a = varying(g, "a", Type::Float);
    Expr u = uniform(g, vector_parameter("u", {1, 2}));
    g.set_output("out", (u * a).id());
    EvalInputs in;
    in.lanes = 600;
    in.varyings["a"] = std::vector<double>(500, 1.0); // enough for the first block only
    CHECK(evaluate(g, "out", in, EvalPrecision::Float).error == "varying 'a' missing or too short");
    in.uniforms["u"] = {1.0}; // fails every block, and comes first in node order
    CHECK(evaluate(g, "out", in, EvalPrecision::Float).error ==
          "uniform 'u': no value with 2 components");
    in.lanes = 0; // nothing to evaluate, nothing to fail
    CHECK(evaluate(g, "out", in, EvalPrecision::Float).ok());
}

TEST_CASE("only_the_selected_case_needs_its_inputs", "[switch]") {
    // The program compiles the case the selector picks (its value computed once, at compile
    // time): a texture only another case samples need not be supplied, as on the GPU.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr sel = uniform(g, {.name = "sel", .type = Type::Float, .default_value = {0.0}, .max = 1.0});
    const auto r = choose(g, sel * 1.0, 2, [&](Graph& body, int c) -> std::vector<Expr> {
        Expr xin = read_in(body, x);
        if (c == 0) return {xin * 3.0};
        return {sample_level(texture(body, {"t", Type::Texture2D, "", ""}), vec2(xin, xin),
                             constant(body, 0.0))
                    .x()};
    });
    REQUIRE(g.diagnostics().empty());
    g.set_output("out", r[0].id());
    EvalInputs in;
    in.varyings["x"] = {0.25, 0.5};
    in.lanes = 2;
    const EvalResult first = evaluate(g, "out", in, EvalPrecision::Float);
    REQUIRE(first.ok());
    CHECK(first.values == std::vector<double>{0.75, 1.5});
    in.uniforms["sel"] = {1.0};
    CHECK(evaluate(g, "out", in, EvalPrecision::Float).error == "texture 't' not supplied");
    const float texel[4] = {0.5f, 0.f, 0.f, 1.f};
    in.textures["t"] = TextureView{1, 1, texel};
    const EvalResult second = evaluate(g, "out", in, EvalPrecision::Float);
    REQUIRE(second.ok());
    CHECK(second.values == std::vector<double>{0.5, 0.5});
}

TEST_CASE("switches_and_loops_nest_in_each_other", "[switch]") {
    // c <- case 0: c + x; case 1: 4c + 1 by an inner loop (c <- 2c + j, j < 2), three times.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr sel = uniform(g, {.name = "sel", .type = Type::Float, .default_value = {0.0}, .max = 1.0});
    const auto r = loop(g, 3, {x}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{choose(c[0].graph(), sel, 2,
                               [&](Graph& body, int k) -> std::vector<Expr> {
                                   Expr cin = read_in(body, c[0]);
                                   if (k == 0) return {cin + read_in(body, x)};
                                   return loop(body, 2, {cin},
                                               [](Expr j, const std::vector<Expr>& d) {
                                                   return LoopStep{{d[0] * 2.0 + j}, {}};
                                               });
                               }),
                        {}};
    });
    REQUIRE(g.diagnostics().empty());
    g.set_output("out", r[0].id());
    EvalInputs in;
    in.varyings["x"] = {0.5, -2.0};
    in.lanes = 2;
    for (double s : {0.0, 1.0}) {
        in.uniforms["sel"] = {s};
        const EvalResult e = evaluate(g, "out", in, EvalPrecision::Double);
        REQUIRE(e.ok());
        const std::vector<double> expected =
            s == 0 ? std::vector<double>{2.0, -8.0} : std::vector<double>{53.0, -107.0};
        CHECK(e.values == expected);
    }
}

TEST_CASE("carried_values_vary_per_lane_where_their_next_values_or_an_exit_make_them", "[loop]") {
    // Every initial value is the same on every lane. a stays so (a <- 2a); b varies from the
    // first step (b <- b + x); c only through b (c <- c + b), which a single pass over the body
    // would miss; an inner loop carries d <- d + a (the same) and e <- e + x (varies). A loop
    // whose lanes leave after different iterations varies even with next = n + 1. The program
    // checks that a value it holds once for all lanes is computed so.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr zero = constant(g, 0.0);
    const auto r = loop(
        g, 4, {constant(g, 1.0), zero, zero, zero, zero}, [&](Expr, const std::vector<Expr>& v) {
            const auto inner =
                loop(v[0].graph(), 2, {v[3], v[4]}, [&](Expr, const std::vector<Expr>& w) {
                    return LoopStep{{w[0] + v[0], w[1] + x}, {}};
                });
            return LoopStep{{v[0] * 2.0, v[1] + x, v[2] + v[1], inner[0], inner[1]}, {}};
        });
    const auto left = loop(g, 8, {zero}, [&](Expr i, const std::vector<Expr>& n) {
        return LoopStep{{n[0] + 1.0}, i < x};
    });
    g.set_output("out", vec4(r[0], r[2], r[3] + r[4], left[0]).id());
    REQUIRE(g.diagnostics().empty());
    EvalInputs in;
    in.varyings["x"] = {1.0, 3.0};
    in.lanes = 2;
    for (EvalPrecision p : {EvalPrecision::Double, EvalPrecision::Float}) {
        const EvalResult e = evaluate(g, "out", in, p);
        REQUIRE(e.ok());
        // a = 16; c = 0 + x + 2x + 3x; d = 2 (1 + 2 + 4 + 8); e = 8x; left after i = x.
        for (size_t l = 0; l < 2; ++l) {
            const double xv = in.varyings["x"][l];
            CHECK(e.values[4 * l] == 16.0);
            CHECK(e.values[4 * l + 1] == 6.0 * xv);
            CHECK(e.values[4 * l + 2] == 30.0 + 8.0 * xv);
            CHECK(e.values[4 * l + 3] == xv + 1.0);
        }
    }
}
