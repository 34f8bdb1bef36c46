#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

#include "watergen/eval/compare/prune_measure.h"
#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/ir/fold/ir_fold.h"
#include "watergen/plan/scene_pruning.h"

using namespace watergen;

namespace {

struct Fixture {
    Graph g;
    Expr x, y, t, tex;
    Fixture() {
        x = varying(g, "x", Type::Float);
        y = varying(g, "y", Type::Float);
        t = uniform(g, {.name = "t",
                        .type = Type::Float,
                        .default_value = {0.5},
                        .max = 1.0,
                        .origin = "test"});
        tex = sample(texture(g, {"img", Type::Texture2D, "", ""}), vec2(x, y)).x();
    }
    // Folds `e` as the only output; returns what the output became.
    FoldResult fold(Expr e, const FoldFacts& f = {}) {
        g.set_output("v", e.id());
        return fold_graph(g, f);
    }
};

const Node& output(const FoldResult& r) {
    return r.graph.node(r.graph.outputs().front().node);
}

bool is_constant(const FoldResult& r, double v) {
    const Node& n = output(r);
    if (n.op != Op::Constant) return false;
    for (double c : n.values)
        if (c != v) return false;
    return true;
}

std::string events(const FoldResult& r) {
    std::string s;
    for (const auto& e : r.report.events)
        s += e.what + "; ";
    return s;
}

} // namespace

TEST_CASE("fixed_parameters_become_constants_and_fold", "[fold]") {
    Fixture f;
    FoldFacts facts;
    facts.fixed["t"] = {{1.0}, facts.add_fact("t = 1", "s.json:3:4 /fixed/t")};
    const FoldResult r = f.fold(f.x * f.t, facts);
    CHECK(output(r).op == Op::Varying); // x * 1 -> x
    CHECK(r.report.folded_parameters.at("t") == std::vector<double>{1.0});
    REQUIRE(r.report.removed_parameters.size() == 1);
    CHECK(r.report.removed_parameters[0].name == "t");
    CHECK(describe_facts(facts, r.report.removed_parameters[0].facts) ==
          "t = 1 [s.json:3:4 /fixed/t]");
    CHECK(r.graph.find_parameter("t") == nullptr); // no longer declared
    CHECK(events(r) == "t is fixed to 1; (... * ...): x * 1 -> x; ");
}

TEST_CASE("identities", "[fold]") {
    auto folds_to_x = [](auto make) {
        Fixture f;
        const FoldResult r = f.fold(make(f));
        INFO(events(r));
        return output(r).op == Op::Varying && output(r).name == "x";
    };
    CHECK(folds_to_x([](Fixture& f) { return f.x + constant(f.g, 0.0); }));
    CHECK(folds_to_x([](Fixture& f) { return constant(f.g, 0.0) + f.x; }));
    CHECK(folds_to_x([](Fixture& f) { return f.x - constant(f.g, 0.0); }));
    CHECK(folds_to_x([](Fixture& f) { return constant(f.g, 1.0) * f.x; }));
    CHECK(folds_to_x([](Fixture& f) { return f.x / constant(f.g, 1.0); }));
    CHECK(folds_to_x([](Fixture& f) { return -(-f.x); }));
    CHECK(folds_to_x([](Fixture& f) { return mix(f.x, f.y, constant(f.g, 0.0)); }));
    CHECK(folds_to_x([](Fixture& f) { return mix(f.y, f.x, constant(f.g, 1.0)); }));
    CHECK(folds_to_x([](Fixture& f) { return mix(f.x, f.x, f.t); }));
    CHECK(folds_to_x([](Fixture& f) { return select(f.y < f.t, f.x, f.x); }));
    CHECK(folds_to_x([](Fixture& f) { return pow(f.x, constant(f.g, 1.0)); }));
    // 0 - x becomes a negation.
    Fixture f;
    CHECK(output(f.fold(constant(f.g, 0.0) - f.x)).op == Op::Neg);
}

TEST_CASE("bounds_decide_min_max_clamp_saturate_and_select", "[fold]") {
    FoldFacts facts;
    facts.input_ranges["x"] = {{make_interval(2.0, 3.0)}, facts.add_fact("x in [2, 3]", "")};
    {
        Fixture f;
        CHECK(output(f.fold(max(f.x, 1.0), facts)).op == Op::Varying);
    }
    {
        Fixture f;
        CHECK(is_constant(f.fold(min(f.x, 1.0), facts), 1.0));
    }
    {
        Fixture f;
        CHECK(is_constant(f.fold(saturate(f.x), facts), 1.0)); // x >= 2: always 1
    }
    {
        Fixture f;
        CHECK(output(f.fold(clamp(f.x, 0.0, 10.0), facts)).op == Op::Varying);
    }
    {
        Fixture f; // t in [0, 1] (declared range) is within [0, 1]
        CHECK(output(f.fold(saturate(f.t), facts)).op == Op::Uniform);
    }
    {
        Fixture f;
        const FoldResult r = f.fold(select(f.x > constant(f.g, 1.5), f.y, f.t), facts);
        CHECK(output(r).op == Op::Varying);
        CHECK(output(r).name == "y");
        CHECK(describe_facts(facts, r.report.events.back().facts) == "x in [2, 3]");
    }
    {
        Fixture f; // undecided: x may be 2.5
        CHECK(output(f.fold(max(f.x, 2.5), facts)).op == Op::Max);
    }
}

TEST_CASE("x_times_zero_folds_only_when_x_is_finite", "[fold]") {
    {
        Fixture f; // a texture sample is finite by the input contract
        CHECK(is_constant(f.fold(f.tex * constant(f.g, 0.0)), 0.0));
    }
    {
        Fixture f; // 1 / y may be infinite (y may be 0): inf * 0 is NaN, so no fold
        CHECK(output(f.fold((1.0 / f.y) * constant(f.g, 0.0))).op == Op::Mul);
    }
    {
        Fixture f; // log(y) may be NaN
        CHECK(output(f.fold(constant(f.g, 0.0) * log(f.y))).op == Op::Mul);
    }
    {
        Fixture f; // y in [1, 2]: 1 / y is finite
        FoldFacts facts;
        facts.input_ranges["y"] = {{make_interval(1.0, 2.0)}, facts.add_fact("y in [1, 2]", "")};
        CHECK(is_constant(f.fold((1.0 / f.y) * constant(f.g, 0.0), facts), 0.0));
    }
}

TEST_CASE("terms_that_vanish_at_depth_fold_to_zero", "[fold]") {
    constexpr Quantity kDepth{"test_depth", Type::Float, ""};
    Fixture f;
    Expr depth = bind(kDepth, named(max(f.x - f.y, 0.0), "water_depth"));
    Expr k = uniform(f.g, {.name = "k",
                           .type = Type::Float,
                           .default_value = {0.1},
                           .max = 10.0,
                           .unit = "1/m",
                           .origin = "test"});
    Expr trans = named(exp(-k * depth), "transmittance");
    FoldFacts facts;
    facts.parameter_ranges["k"] = {{make_interval(0.05, 2.0)},
                                   facts.add_fact("k in [0.05, 2]", "")};
    facts.quantity_ranges[kDepth] = {{make_interval(400.0, 4000.0)},
                                     facts.add_fact("depth 400..4000 m", "d.json:5:3")};
    const FoldResult r = f.fold(f.tex + f.tex * trans, facts);
    CHECK(output(r).op == Op::Swizzle); // tex + tex * 0 -> tex
    bool found = false;
    for (const auto& t : r.report.removed)
        if (t.name == "transmittance") {
            found = true;
            REQUIRE(t.event >= 0);
            const FoldEvent& e = r.report.events[static_cast<size_t>(t.event)];
            CHECK(e.what.find("transmittance vanishes") == 0);
            // The cause: the depth and the absorption range, not every fact near it.
            CHECK(describe_facts(facts, e.facts) ==
                  "k in [0.05, 2]; depth 400..4000 m [d.json:5:3]");
        }
    CHECK(found);
    // Without the depth fact nothing vanishes.
    FoldFacts shallow = facts;
    shallow.quantity_ranges.clear();
    Fixture g2;
    Expr d2 = bind(kDepth, named(max(g2.x - g2.y, 0.0), "water_depth"));
    Expr k2 = uniform(g2.g, {.name = "k",
                             .type = Type::Float,
                             .default_value = {0.1},
                             .max = 10.0,
                             .unit = "1/m",
                             .origin = "test"});
    CHECK(output(g2.fold(g2.tex + g2.tex * named(exp(-k2 * d2), "transmittance"), shallow)).op ==
          Op::Add);
}

TEST_CASE("constant_subexpressions_are_evaluated_like_the_cpu_evaluator", "[fold]") {
    Fixture f;
    const FoldResult r = f.fold(f.x + sqrt(constant(f.g, 2.0)) * exp(constant(f.g, 1.0)));
    const Node& n = output(r);
    REQUIRE(n.op == Op::Add);
    const Node& c = r.graph.node(n.args[1]);
    REQUIRE(c.op == Op::Constant);
    CHECK(c.values[0] == std::sqrt(2.0) * std::exp(1.0));
    CHECK(r.report.events.empty()); // no scene fact involved: nothing to explain
}

TEST_CASE("bools_are_never_made_constants", "[fold]") {
    Fixture f;
    FoldFacts facts;
    facts.input_ranges["x"] = {{make_interval(2.0, 3.0)}, facts.add_fact("x in [2, 3]", "")};
    // The comparison is decided but only its select folds; no bool literal is emitted.
    const FoldResult r = f.fold(select(f.x > constant(f.g, 1.0), f.y, f.x) + f.t, facts);
    for (uint32_t id : r.graph.live_nodes())
        CHECK_FALSE((r.graph.node(id).op == Op::Constant && r.graph.node(id).type == Type::Bool));
}

TEST_CASE("folded_example_shaders_compute_what_the_unfolded_ones_compute", "[fold]") {
    // For every variant each example scene reaches: the CPU evaluator over the synthetic scene
    // conformed to the scene's facts gives the same image folded and unfolded.
    const char* src = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(src);
    const Material m = default_material();
    const SyntheticScene base = make_synthetic_scene(32, 32);
    for (const char* name : {"open_ocean", "harbour_night", "mountain_lake"}) {
        Diagnostics ds;
        const auto facts = load_scene(std::string(src) + "/examples/scenes/" + name + ".json", ds);
        REQUIRE(facts);
        const auto plan = plan_scene(m, *facts, ds);
        REQUIRE(plan);
        const SyntheticScene scene = conform_scene(base, *plan, m);
        for (const Variant& v : plan->variants) {
            INFO(name << ": " << v.key());
            const WaterShader s = m.compose(v);
            REQUIRE_FALSE(has_errors(s.fragment.diagnostics()));
            const FoldResult r = fold_graph(s.fragment, plan->facts);
            CHECK(r.report.live_after < r.report.live_before);
            const EvalResult a = evaluate_image(s.fragment, "color", scene.eval_inputs(), 32, 32,
                                                EvalPrecision::Double);
            const EvalResult b = evaluate_image(r.graph, "color", scene.eval_inputs(), 32, 32,
                                                EvalPrecision::Double);
            REQUIRE(a.ok());
            REQUIRE(b.ok());
            double worst = 0;
            for (size_t i = 0; i < a.values.size(); ++i)
                worst = std::max(worst, std::fabs(a.values[i] - b.values[i]));
            CHECK(worst < 1e-6);
        }
    }
}

TEST_CASE("variants_that_fold_alike_give_the_same_graph", "[fold]") {
    const char* src = std::getenv("WATERGEN_SOURCE_DIR");
    REQUIRE(src);
    Diagnostics ds;
    const auto facts = load_scene(std::string(src) + "/examples/scenes/open_ocean.json", ds);
    REQUIRE(facts);
    const Material m = default_material();
    const auto plan = plan_scene(m, *facts, ds);
    REQUIRE(plan);
    Variant hard = plan->variants.front(), soft = hard;
    REQUIRE_FALSE(set_choice(hard, "shore", "hard"));
    REQUIRE_FALSE(set_choice(soft, "shore", "soft"));
    // 400 m of water at hardness >= 0.5: the soft shore blend is always 1.
    const FoldResult a = fold_graph(m.compose(hard).fragment, plan->facts);
    const FoldResult b = fold_graph(m.compose(soft).fragment, plan->facts);
    Diagnostics ignored;
    CHECK(emit_fragment(a.graph, Language::Glsl, "f", "k", ignored).source ==
          emit_fragment(b.graph, Language::Glsl, "f", "k", ignored).source);
}
