// Bounded loops in the IR: the DSL builds them, the emitters write them as `for` loops, the
// CPU evaluator runs them per lane with per-lane exits.
#include <catch2/catch.hpp>

#include <cmath>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/ir/fold/ir_fold.h"

using namespace watergen;

namespace {

EvalInputs lanes_of(const std::string& name, const std::vector<double>& values) {
    EvalInputs in;
    in.varyings[name] = values;
    in.lanes = values.size();
    return in;
}

size_t occurrences(const std::string& text, const std::string& part) {
    size_t count = 0;
    for (size_t p = text.find(part); p != std::string::npos; p = text.find(part, p + 1))
        ++count;
    return count;
}

// Heron's square root of x from 1 + x / 2, stopping once a step changes less than 1e-12
// relative; the second carried value counts the iterations run.
Graph heron(int trip_count) {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = loop(g, trip_count, {1.0 + x * 0.5, constant(g, 0.0)},
                        [&](Expr, const std::vector<Expr>& c) {
                            Expr next = 0.5 * (c[0] + x / c[0]);
                            return LoopStep{{next, c[1] + 1.0}, abs(next - c[0]) > 1e-12 * next};
                        });
    g.set_output("root", r[0].id());
    g.set_output("steps", r[1].id());
    return g;
}

} // namespace

TEST_CASE("a_loop_sums_over_its_iterations", "[loop]") {
    // s = sum over i of (i * x + k), k an outer value computed once and captured.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr k = named(sin(x) * 2.0, "outer_k");
    const auto r = loop(g, 10, {constant(g, 0.0)}, [&](Expr i, const std::vector<Expr>& c) {
        return LoopStep{{c[0] + i * x + k}, Expr()};
    });
    g.set_output("s", r[0].id());
    REQUIRE(g.diagnostics().empty());
    const EvalResult e = evaluate(g, "s", lanes_of("x", {0.0, 1.0, -2.5}), EvalPrecision::Double);
    REQUIRE(e.ok());
    for (size_t l = 0; l < 3; ++l) {
        const double xv = std::vector<double>{0.0, 1.0, -2.5}[l];
        CHECK(e.values[l] == Approx(45.0 * xv + 10.0 * 2.0 * std::sin(xv)).epsilon(1e-14));
    }
}

TEST_CASE("each_lane_leaves_a_loop_when_its_condition_fails", "[loop]") {
    const Graph g = heron(64);
    const std::vector<double> xs = {1.0, 2.0, 1e6, 1e-6};
    const EvalResult root = evaluate(g, "root", lanes_of("x", xs), EvalPrecision::Double);
    const EvalResult steps = evaluate(g, "steps", lanes_of("x", xs), EvalPrecision::Double);
    REQUIRE(root.ok());
    for (size_t l = 0; l < xs.size(); ++l) {
        INFO("x = " << xs[l]);
        CHECK(root.values[l] == Approx(std::sqrt(xs[l])).epsilon(1e-12));
        CHECK(steps.values[l] < 64); // left early, each after its own count
    }
    CHECK(steps.values[0] < steps.values[2]); // 1e6 starts far from its root
    // With too few iterations the exit never comes: the trip count bounds the loop.
    const EvalResult capped = evaluate(heron(3), "steps", lanes_of("x", xs), EvalPrecision::Double);
    CHECK(capped.values[2] == 3.0);
}

TEST_CASE("loops_are_emitted_as_for_loops_in_both_languages", "[loop]") {
    const Graph g = heron(16);
    Graph frag;
    Expr uv = varying(frag, "v_uv", Type::Vec2);
    const auto r = loop(frag, 16, {uv.x() + 1.0}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{0.5 * (c[0] + uv.y() / c[0])}, Expr()};
    });
    frag.set_output("color", vec4(r[0], uv.y(), constant(frag, 0.0), constant(frag, 1.0)).id());
    Diagnostics ds;
    const EmittedShader glsl = emit_fragment(frag, Language::Glsl, "f.glsl", "k", ds);
    const EmittedShader hlsl = emit_fragment(frag, Language::Hlsl, "f.hlsl", "k", ds);
    CHECK(ds.empty());
    CHECK(glsl.source.find("#extension GL_EXT_control_flow_attributes : require") !=
          std::string::npos);
    CHECK(glsl.source.find("[[dont_unroll]] for (int ") != std::string::npos);
    CHECK(hlsl.source.find("[loop] for (int ") != std::string::npos);
    // The body is written once, not 16 times.
    CHECK(occurrences(glsl.source, " / ") == 1);
}

TEST_CASE("the_emit_options_override_every_loops_unroll_hint", "[loop]") {
    // One loop hinted to unroll, one not: "hinted" keeps each, "all" / "none" set both.
    Graph frag;
    Expr uv = varying(frag, "v_uv", Type::Vec2);
    auto step = [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{c[0] * 0.5 + uv.y()}, Expr()};
    };
    const auto a = loop(frag, 4, {uv.x()}, step, LoopOptions{UnrollHint::Unroll});
    const auto b = loop(frag, 5, {uv.y()}, step);
    frag.set_output("color", vec4(a[0], b[0], constant(frag, 0.0), constant(frag, 1.0)).id());
    auto count = [](const std::string& text, const std::string& word) {
        size_t n = 0;
        for (size_t p = text.find(word); p != std::string::npos; p = text.find(word, p + 1))
            ++n;
        return n;
    };
    const std::vector<std::pair<LoopUnroll, std::pair<size_t, size_t>>> cases = {
        {LoopUnroll::AsHinted, {1, 1}}, {LoopUnroll::All, {2, 0}}, {LoopUnroll::None, {0, 2}}};
    for (const auto& [policy, expected] : cases) {
        Diagnostics ds;
        EmitOptions options;
        options.unroll = policy;
        const std::string glsl =
            emit_fragment(frag, Language::Glsl, "f.glsl", "k", ds, options).source;
        const std::string hlsl =
            emit_fragment(frag, Language::Hlsl, "f.hlsl", "k", ds, options).source;
        CHECK(ds.empty());
        CHECK(count(glsl, "[[unroll]] for") == expected.first);
        CHECK(count(glsl, "[[dont_unroll]] for") == expected.second);
        CHECK(count(hlsl, "[unroll] for") == expected.first);
        CHECK(count(hlsl, "[loop] for") == expected.second);
    }
}

TEST_CASE("a_malformed_loop_is_a_diagnostic", "[loop]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    loop(g, 4, {x}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{vec2(c[0], c[0])}, Expr()};
    });
    loop(g, 4, {x}, [&](Expr, const std::vector<Expr>&) { return LoopStep{{}, Expr()}; });
    loop(g, 0, {x}, [&](Expr, const std::vector<Expr>& c) { return LoopStep{c, Expr()}; });
    loop(g, 4, {x}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{ddx(c[0])}, Expr()};
    });
    loop(g, 4, {x}, [&](Expr, const std::vector<Expr>& c) { return LoopStep{c, c[0]}; });
    std::string all;
    for (const auto& d : g.diagnostics())
        all += d.message + "\n";
    INFO(all);
    CHECK(all.find("carried value 0 starts as float and comes back as vec2") != std::string::npos);
    CHECK(all.find("the body returns 0 carried values for 1") != std::string::npos);
    CHECK(all.find("trip count 0 is not in 1..4096") != std::string::npos);
    CHECK(all.find("may not take ddx / ddy") != std::string::npos);
    CHECK(all.find("the exit condition is float, not bool") != std::string::npos);
}

TEST_CASE("the_fold_keeps_a_loop_whose_inputs_are_all_constants", "[loop]") {
    // Nothing but constants go in (a scene fact can make every captured value one); the loop
    // still runs, and what it computes is unchanged.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = loop(g, 5, {constant(g, 1.0)}, [&](Expr i, const std::vector<Expr>& c) {
        return LoopStep{{c[0] * 2.0 + i}, Expr()};
    });
    g.set_output("v", (r[0] + x * 0.0).id());
    const FoldResult folded = fold_graph(g, {});
    REQUIRE(folded.graph.diagnostics().empty());
    const EvalResult e = evaluate(folded.graph, "v", lanes_of("x", {3.0}), EvalPrecision::Double);
    REQUIRE(e.ok());
    CHECK(e.values[0] == 58.0); // c = 2c + i from 1, five times
}

namespace {

// The fold of `value` with x in [0, 1]: the rewrites it made, one per line.
std::string fold_events(Graph& g, Expr value) {
    g.set_output("v", value.id());
    FoldFacts facts;
    facts.input_ranges["x"] = {{make_interval(0.0, 1.0)}, facts.add_fact("x in [0, 1]", "")};
    const FoldResult folded = fold_graph(g, facts);
    std::string all;
    for (const auto& e : folded.report.events)
        all += e.what + "\n";
    return all;
}

// s = sum of (i + 1) over the iterations run, for a trip count read from parameter "n": the
// sum tells how many ran.
Graph counted(Expr (*count)(Graph&)) {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r =
        loop(g, count(g), 8, {constant(g, 0.0)}, [&](Expr i, const std::vector<Expr>& c) {
            return LoopStep{{c[0] + i + 1.0}, Expr()};
        });
    g.set_output("s", (r[0] + x * 0.0).id());
    return g;
}

Expr count_parameter(Graph& g) {
    return uniform(g, {.name = "n", .type = Type::Float, .default_value = {3.0}, .max = 100.0});
}

double sum_for_count(const Graph& g, double n) {
    EvalInputs in = lanes_of("x", {1.0, 2.0});
    in.uniforms["n"] = {n};
    const EvalResult e = evaluate(g, "s", in, EvalPrecision::Float);
    REQUIRE(e.ok());
    CHECK(e.values[0] == e.values[1]); // every lane runs the same count
    return e.values[0];
}

} // namespace

TEST_CASE("the_fold_bounds_a_loop_by_running_its_body_over_intervals", "[loop]") {
    // c = c / 2 + x from c = x, eight times: c stays in [0, 2) for x in [0, 1].
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = loop(g, 8, {x}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{c[0] * 0.5 + x}, Expr()};
    });
    const std::string events = fold_events(g, min(max(r[0], constant(g, 0.0)), 2.0));
    INFO(events);
    CHECK(events.find("max(a, b) -> a (a >= b)") != std::string::npos);
    CHECK(events.find("min(a, b) -> a (a <= b)") != std::string::npos);
}

TEST_CASE("a_loop_bound_holds_for_every_iteration_count_an_exit_allows", "[loop]") {
    // With an exit the loop ends after any of its 64 iterations: the count is in [0, 64] (the
    // union of every state; each + 1 widened by its rounding margin), so min(count, 64.01)
    // folds and min(count, 63) must not.
    for (const double cap : {64.01, 63.0}) {
        Graph g;
        Expr x = varying(g, "x", Type::Float);
        const auto r = loop(g, 64, {constant(g, 0.0), x}, [&](Expr, const std::vector<Expr>& c) {
            Expr next = c[1] * c[1];
            return LoopStep{{c[0] + 1.0, next}, next > 1e-6};
        });
        const std::string events = fold_events(g, min(r[0], cap));
        INFO("cap " << cap << "\n" << events);
        CHECK((events.find("min(a, b) -> a (a <= b)") != std::string::npos) == (cap > 64.0));
    }
}

TEST_CASE("a_long_loop_is_widened_then_narrowed_to_a_sound_bound", "[loop]") {
    // 1000 steps, past what the analysis follows step by step. c / 2 + x converges below 2:
    // widened to a threshold, then narrowed, its bound ends within 2.5.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = loop(g, 1000, {x}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{c[0] * 0.5 + x}, Expr()};
    });
    const std::string events = fold_events(g, min(r[0], 2.5));
    INFO(events);
    CHECK(events.find("min(a, b) -> a (a <= b)") != std::string::npos);
}

TEST_CASE("a_growing_loop_is_widened_without_claiming_a_bound_it_cannot_hold", "[loop]") {
    // c + x grows every step: its upper bound is widened to infinity, so min(c, 999) stays
    // (c reaches 1000 at x = 1), and so does max(c, 0) (c is not proven finite).
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = loop(g, 1000, {constant(g, 0.0)}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{c[0] + x}, Expr()};
    });
    const std::string events = fold_events(g, min(max(r[0], constant(g, 0.0)), 999.0));
    INFO(events);
    CHECK(events.find("min(a, b)") == std::string::npos);
    const EvalResult e = evaluate(g, "v", lanes_of("x", {1.0}), EvalPrecision::Double);
    REQUIRE(e.ok());
    CHECK(e.values[0] == 999.0);
}

TEST_CASE("nested_loops_are_bounded_through_both_bodies", "[loop]") {
    // An outer loop of 4 adds an inner loop's sum of 3 copies of x: at most 12 for x <= 1.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = loop(g, 4, {constant(g, 0.0)}, [&](Expr, const std::vector<Expr>& outer) {
        const auto inner = loop(outer[0].graph(), 3, {constant(outer[0].graph(), 0.0)},
                                [&](Expr, const std::vector<Expr>& c) {
                                    return LoopStep{{c[0] + x}, Expr()};
                                });
        return LoopStep{{outer[0] + inner[0]}, Expr()};
    });
    const std::string events = fold_events(g, min(r[0], 12.01));
    INFO(events);
    CHECK(events.find("min(a, b) -> a (a <= b)") != std::string::npos);
    const EvalResult e = evaluate(g, "v", lanes_of("x", {1.0}), EvalPrecision::Double);
    REQUIRE(e.ok());
    CHECK(e.values[0] == 12.0);
}

TEST_CASE("a_loop_runs_the_trip_count_its_parameter_gives_floored_and_bounded", "[loop]") {
    const Graph g = counted(&count_parameter);
    REQUIRE(g.diagnostics().empty());
    CHECK(sum_for_count(g, 0.0) == 0.0);
    CHECK(sum_for_count(g, 1.0) == 1.0);
    CHECK(sum_for_count(g, 3.0) == 6.0);
    CHECK(sum_for_count(g, 3.9) == 6.0);  // floored
    CHECK(sum_for_count(g, 0.5) == 0.0);  // below 1: none
    CHECK(sum_for_count(g, -2.0) == 0.0); // clamped at 0
    CHECK(sum_for_count(g, 8.0) == 36.0); // the maximum
    CHECK(sum_for_count(g, 50.0) == 36.0);
    CHECK(sum_for_count(g, INFINITY) == 36.0);
    CHECK(sum_for_count(g, NAN) == 0.0);
}

TEST_CASE("a_trip_count_from_data_is_emitted_as_a_break_before_the_body", "[loop]") {
    Graph frag;
    Expr uv = varying(frag, "v_uv", Type::Vec2);
    Expr n =
        uniform(frag, {.name = "n", .type = Type::Float, .default_value = {3.0}, .max = 100.0});
    const auto r = loop(frag, n, 8, {uv.x()}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{c[0] * uv.y()}, Expr()};
    });
    frag.set_output("color", vec4(r[0], uv.y(), constant(frag, 0.0), constant(frag, 1.0)).id());
    Diagnostics ds;
    const EmittedShader glsl = emit_fragment(frag, Language::Glsl, "f.glsl", "k", ds);
    const EmittedShader hlsl = emit_fragment(frag, Language::Hlsl, "f.hlsl", "k", ds);
    INFO(glsl.source);
    CHECK(ds.empty());
    CHECK(glsl.source.find("float trip_count = floor(params.n);") != std::string::npos);
    CHECK(glsl.source.find("< 8; ++loop") != std::string::npos);
    CHECK(glsl.source.find(" < trip_count)) break;") != std::string::npos);
    CHECK(hlsl.source.find("float trip_count = floor(n);") != std::string::npos);
    CHECK(hlsl.source.find("if (!(((float)loop") != std::string::npos);
    // As a specialization constant the count is read by name.
    const EmittedShader spec =
        emit_fragment(frag, Language::Glsl, "f.glsl", "k", ds, EmitOptions{false, {"n"}});
    CHECK(ds.empty());
    CHECK(spec.source.find("float trip_count = floor(n);") != std::string::npos);
}

TEST_CASE("a_trip_count_that_differs_between_pixels_is_a_diagnostic", "[loop]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr n = uniform(g, {.name = "n", .type = Type::Float, .default_value = {3.0}, .max = 100.0});
    auto body = [](Expr, const std::vector<Expr>& c) { return LoopStep{c, Expr()}; };
    loop(g, n + x, 8, {x}, body);
    loop(g, vec2(n, n), 8, {x}, body);
    loop(g, n, 0, {x}, body);
    // Inside a body: the outer loop's index is not the same for every pixel, a parameter
    // captured through the body is.
    loop(g, 4, {x}, [&](Expr i, const std::vector<Expr>& c) {
        loop(i.graph(), i, 8, {c[0]}, body);
        return LoopStep{loop(i.graph(), n * 2.0, 8, {c[0]}, body), Expr()};
    });
    std::string all;
    for (const auto& d : g.diagnostics())
        all += d.message + "\n";
    INFO(all);
    CHECK(all.find("the trip count must be the same for every pixel (parameters and constants "
                   "only), but it reads varying 'x'") != std::string::npos);
    CHECK(all.find("the trip count is vec2, not float") != std::string::npos);
    CHECK(all.find("maximum trip count 0 is not in 1..4096") != std::string::npos);
    CHECK(all.find("but it reads a loop index") != std::string::npos);
    CHECK(g.diagnostics().size() == 4);
}

TEST_CASE("nested_loops_capture_across_two_levels", "[loop]") {
    // s = sum over i < 3 of sum over j < n of (x + k) * (i + 1): the inner body reads x and
    // k from the outermost graph and the outer loop's index.
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr k = named(x * x, "outer_k");
    Expr n = count_parameter(g);
    const auto r = loop(g, 3, {constant(g, 0.0)}, [&](Expr i, const std::vector<Expr>& c) {
        const auto inner = loop(i.graph(), n, 4, {c[0]}, [&](Expr, const std::vector<Expr>& d) {
            return LoopStep{{d[0] + (x + k) * (i + 1.0)}, Expr()};
        });
        return LoopStep{inner, Expr()};
    });
    g.set_output("s", r[0].id());
    REQUIRE(g.diagnostics().empty());
    for (double count : {0.0, 2.0, 3.0, 9.0}) {
        EvalInputs in = lanes_of("x", {0.5, -3.0});
        in.uniforms["n"] = {count};
        const EvalResult e = evaluate(g, "s", in, EvalPrecision::Double);
        REQUIRE(e.ok());
        const double runs = std::min(count, 4.0);
        for (size_t l = 0; l < 2; ++l) {
            const double xv = l == 0 ? 0.5 : -3.0;
            CHECK(e.values[l] == Approx(6.0 * runs * (xv + xv * xv)).epsilon(1e-14));
        }
    }
    Diagnostics ds;
    Graph frag;
    Expr uv = varying(frag, "v_uv", Type::Vec2);
    Expr m = count_parameter(frag);
    const auto f = loop(frag, 3, {uv.x()}, [&](Expr i, const std::vector<Expr>& c) {
        return LoopStep{loop(i.graph(), m, 4, {c[0]},
                             [&](Expr, const std::vector<Expr>& d) {
                                 return LoopStep{{d[0] * uv.y() + i}, Expr()};
                             }),
                        Expr()};
    });
    frag.set_output("color", vec4(f[0], uv.y(), constant(frag, 0.0), constant(frag, 1.0)).id());
    const EmittedShader glsl = emit_fragment(frag, Language::Glsl, "f.glsl", "k", ds);
    INFO(glsl.source);
    CHECK(ds.empty());
    CHECK(occurrences(glsl.source, "for (int ") == 2);
}

TEST_CASE("the_fold_keeps_a_counted_loop_and_its_count", "[loop]") {
    const Graph g = counted(&count_parameter);
    // Unknown count: the loop and the parameter stay.
    const FoldResult open = fold_graph(g, {});
    CHECK(open.graph.find_parameter("n") != nullptr);
    CHECK(sum_for_count(open.graph, 2.0) == 3.0);
    // A fixed count becomes a constant argument; the loop runs it.
    FoldFacts facts;
    facts.fixed["n"] = {{4.0}, 0};
    const FoldResult fixed = fold_graph(g, facts);
    REQUIRE(fixed.graph.diagnostics().empty());
    CHECK(fixed.graph.find_parameter("n") == nullptr);
    const EvalResult e = evaluate(fixed.graph, "s", lanes_of("x", {1.0}), EvalPrecision::Double);
    REQUIRE(e.ok());
    CHECK(e.values[0] == 10.0);
}

TEST_CASE("a_loop_bound_with_a_trip_count_from_data_holds_for_no_iteration", "[loop]") {
    // Four halvings from 10 end at 0.625, but a count of 0 runs none and gives 10: the bound
    // of a counted loop is the union of every state, the initial one included, so
    // max(result, 5) must stay (a bound of the fourth state alone would fold it to 5).
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr n = uniform(g, {.name = "n", .type = Type::Float, .default_value = {4.0}, .max = 100.0});
    const auto r = loop(g, n, 4, {constant(g, 10.0)}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{c[0] * 0.5}, Expr()};
    });
    const std::string events = fold_events(g, max(r[0] + x * 0.0, constant(g, 5.0)));
    INFO(events);
    CHECK(events.find("max(a, b)") == std::string::npos);
    const FoldResult folded = fold_graph(g, {});
    for (const double count : {0.0, 4.0}) {
        EvalInputs in = lanes_of("x", {1.0});
        in.uniforms["n"] = {count};
        const EvalResult e = evaluate(folded.graph, "v", in, EvalPrecision::Double);
        REQUIRE(e.ok());
        CHECK(e.values[0] == (count == 0.0 ? 10.0 : 5.0));
    }
}

namespace {

// The loop's value as a fragment shader's colour: x from v_uv.x.
void set_colour(Graph& g, Expr value) {
    g.set_output("color", vec4(value, constant(g, 0.0), constant(g, 0.0), constant(g, 1.0)).id());
}

// c = c + x + t (i + 1) over four iterations, t a parameter in [0, 10].
Graph drifting_sum() {
    Graph g;
    Expr x = varying(g, "v_uv", Type::Vec2).x();
    Expr t = uniform(
        g, {.name = "t", .type = Type::Float, .default_value = {1.0}, .max = 10.0, .unit = "s"});
    const auto r = loop(g, 4, {constant(g, 0.0)}, [&](Expr i, const std::vector<Expr>& c) {
        return LoopStep{{c[0] + x + t * (i + 1.0)}, Expr()};
    });
    set_colour(g, r[0]);
    return g;
}

std::string glsl_of(const Graph& g) {
    Diagnostics ds;
    const EmittedShader e = emit_fragment(g, Language::Glsl, "f.frag", "test", ds);
    INFO((ds.empty() ? "" : ds[0].message));
    REQUIRE(ds.empty());
    return e.source;
}

// The red channel per lane, x = v_uv.x per lane, t = 0.
std::vector<double> reds(const Graph& g, const std::vector<double>& xs, EvalPrecision p) {
    EvalInputs in;
    for (double x : xs)
        in.varyings["v_uv"].insert(in.varyings["v_uv"].end(), {x, 0.5});
    in.lanes = xs.size();
    in.uniforms["t"] = {0.0};
    const EvalResult e = evaluate(g, "color", in, p);
    REQUIRE(e.ok());
    std::vector<double> out;
    for (size_t l = 0; l < xs.size(); ++l)
        out.push_back(e.values[l * 4]);
    return out;
}

FoldResult fold_with_t_zero(const Graph& g) {
    FoldFacts facts;
    facts.fixed["t"] = {{0.0}, facts.add_fact("t = 0", "")};
    FoldResult folded = fold_graph(g, facts);
    REQUIRE(folded.graph.diagnostics().empty());
    return folded;
}

} // namespace

TEST_CASE("the_fold_simplifies_inside_a_loop_body_by_what_every_iteration_sees", "[loop]") {
    // With t fixed to 0, t (i + 1) is 0 in every iteration (i + 1 lies in [1, 4]): the body
    // keeps c + x, and the block no longer holds t.
    const Graph g = drifting_sum();
    const FoldResult folded = fold_with_t_zero(g);
    const std::string before = glsl_of(g), after = glsl_of(folded.graph);
    INFO(after);
    CHECK(before.find("params.t") != std::string::npos);
    CHECK(after.find("params.t") == std::string::npos);
    CHECK(after.find("0.0 *") == std::string::npos);
    CHECK(after.find("for (") != std::string::npos); // still a loop
    const auto unfolded = reds(g, {0.25, -3.0}, EvalPrecision::Double);
    CHECK(reds(folded.graph, {0.25, -3.0}, EvalPrecision::Double) == unfolded);
    CHECK(unfolded[0] == 1.0); // four times x
}

TEST_CASE("the_fold_leaves_a_body_term_whose_carried_value_may_overflow", "[loop]") {
    // c doubles 200 times from 1: past the largest float it is infinite, and 0 c is NaN there,
    // so c + 0 c is not c; the analysis widens c to infinity and must keep the product.
    Graph g;
    Expr x = varying(g, "v_uv", Type::Vec2).x();
    Expr t = uniform(
        g, {.name = "t", .type = Type::Float, .default_value = {1.0}, .max = 10.0, .unit = "s"});
    const auto r = loop(g, 200, {constant(g, 1.0)}, [&](Expr, const std::vector<Expr>& c) {
        return LoopStep{{c[0] * 2.0 + t * c[0]}, Expr()};
    });
    set_colour(g, r[0] + x);
    const FoldResult folded = fold_with_t_zero(g);
    const std::string after = glsl_of(folded.graph);
    INFO(after);
    CHECK(after.find("0.0 *") != std::string::npos);
    CHECK(std::isnan(reds(g, {0.0}, EvalPrecision::Float)[0]));
    CHECK(std::isnan(reds(folded.graph, {0.0}, EvalPrecision::Float)[0])); // as the loop computes
}
