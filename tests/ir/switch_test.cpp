// Uniform choices in the IR: choose() builds a switch whose cases are graphs, the emitters write
// it as an if / else-if chain, the CPU evaluator runs the selected case, and the fold pass
// bounds its results by the union of the cases or inlines a decided case.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/ir/fold/ir_fold.h"
#include "watergen/toolchain/toolchain.h"

using namespace watergen;

namespace {

const Parameter kSelector{.name = "sel", .type = Type::Float, .default_value = {0.0}, .max = 2.0};
const Quantity kDoubled{"doubled", Type::Float, ""};

// color = (r, x, 0, 1) with r from three cases: 2x, sin(x) + k (k computed outside), x + ddx(x)
// * 0 + 10 (a derivative, which a case may take). `specialized`: the selector is a constant.
Graph three_cases(bool specialized = false) {
    Graph g;
    Expr uv = varying(g, "v_uv", Type::Vec2);
    Expr x = uv.x();
    Expr k = named(cos(x) * 3.0, "outer_k");
    Parameter sel = kSelector;
    sel.specialization = specialized;
    const auto r = choose(g, uniform(g, sel), 3, [&](Graph& body, int c) -> std::vector<Expr> {
        OriginScope scope(body, "case" + std::to_string(c));
        Expr xin = read_in(body, x);
        if (c == 0) return {bind(kDoubled, named(xin * 2.0, "doubled")), x};
        if (c == 1) return {named(sin(xin) + k, "wavy"), x};
        return {xin + ddx(xin) * 0.0 + 10.0, x};
    });
    REQUIRE(r.size() == 2);
    CHECK(r[1].id() == x.id()); // passed through by every case: the outer value itself
    g.set_output("color", vec4(r[0], x, constant(g, 0.0), constant(g, 1.0)).id());
    return g;
}

EvalInputs pixels(const std::vector<double>& xs, double selector) {
    EvalInputs in;
    for (double x : xs)
        for (double v : {x, 0.5})
            in.varyings["v_uv"].push_back(v);
    in.lanes = xs.size();
    in.uniforms["sel"] = {selector};
    return in;
}

std::string messages(const Graph& g) {
    std::string all;
    for (const auto& d : g.diagnostics())
        all += d.message + "\n";
    return all;
}

size_t count_ops(const Graph& g, Op op) {
    size_t n = 0;
    for (uint32_t id : g.live_nodes())
        n += g.node(id).op == op ? 1 : 0;
    return n;
}

} // namespace

TEST_CASE("the_cpu_evaluator_runs_the_selected_case", "[switch]") {
    const Graph g = three_cases();
    REQUIRE(g.diagnostics().empty());
    const std::vector<double> xs = {0.0, 0.25, 0.5, 1.0};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (double selector : {0.0, 1.0, 2.0, 7.0, -1.0, nan}) {
        INFO("selector " << selector);
        const EvalResult e = evaluate(g, "color", pixels(xs, selector), EvalPrecision::Double);
        REQUIRE(e.ok());
        for (size_t l = 0; l < xs.size(); ++l) {
            const double x = xs[l];
            const double expected = selector == 0.0   ? 2.0 * x
                                    : selector == 1.0 ? std::sin(x) + std::cos(x) * 3.0
                                                      : x + 10.0; // any other value: the last
            CHECK(e.values[l * 4] == Approx(expected).epsilon(1e-15));
            CHECK(e.values[l * 4 + 1] == x);
        }
    }
}

TEST_CASE("a_switch_is_emitted_as_an_if_chain_in_both_languages", "[switch]") {
    for (bool specialized : {false, true}) {
        const Graph g = three_cases(specialized);
        Diagnostics ds;
        const EmittedShader glsl = emit_fragment(g, Language::Glsl, "f.glsl", "k", ds);
        const EmittedShader hlsl = emit_fragment(g, Language::Hlsl, "f.hlsl", "k", ds);
        REQUIRE(ds.empty());
        INFO(glsl.source);
        INFO(hlsl.source);
        for (const EmittedShader* s : {&glsl, &hlsl}) {
            const std::string& src = s->source;
            // GLSL reads block members through the block's instance name; HLSL by name.
            const std::string sel = specialized || s == &hlsl ? "sel" : "params.sel";
            const size_t first = src.find("if (" + sel + " == 0.0) {");
            const size_t second = src.find("} else if (" + sel + " == 1.0) {");
            const size_t last = src.find("} else {");
            REQUIRE(first != std::string::npos);
            REQUIRE(second != std::string::npos);
            REQUIRE(last != std::string::npos);
            CHECK((first < second && second < last));
            // The results are declared before the chain; each case's work is inside its block.
            CHECK(src.find("choice") < first);
            const size_t sine = src.find("sin(");
            CHECK((sine > second && sine < last));
            CHECK(src.find("outer_k") < first); // computed outside, read by case 1
            // Lines of a case belong to the node that wrote them.
            const size_t line =
                static_cast<size_t>(std::count(src.begin(), src.begin() + sine, '\n'));
            CHECK(s->line_origin[line] == "case1");
        }
        CHECK((glsl.source.find("layout(constant_id = 0) const float sel") != std::string::npos) ==
              specialized);
        for (const EmittedShader* s : {&glsl, &hlsl}) {
            const ToolchainOutputs t =
                run_toolchain({s == &glsl ? SourceLanguage::Glsl : SourceLanguage::Hlsl,
                               ShaderStage::Fragment, s->source, s->file_name, "main"});
            std::string all;
            for (const auto& d : t.diagnostics)
                all += format_diagnostic(d) + "\n";
            INFO(all);
            CHECK(t.ok());
        }
    }
}

TEST_CASE("a_selector_must_be_the_same_on_every_pixel", "[switch]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    Expr p = uniform(g, kSelector);
    auto one = [&](Graph&, int) { return std::vector<Expr>{x}; };
    CHECK(choose(g, floor(p * 2.0), 2, one).size() == 1); // computed from parameters: fine
    CHECK(g.diagnostics().empty());
    CHECK(choose(g, x, 2, one).empty());
    CHECK(choose(g, floor(p + sample(texture(g, {"t", Type::Texture2D, "", ""}), vec2(x, x)).x()),
                 2, one)
              .empty());
    CHECK(choose(g, vec2(p, p), 2, one).empty());
    CHECK(choose(g, p, 0, one).empty());
    choose(g, p, 2, [&](Graph& body, int c) {
        return c == 0 ? std::vector<Expr>{x} : std::vector<Expr>{vec2(read_in(body, x), x)};
    });
    choose(g, p, 2, [&](Graph&, int c) {
        return c == 0 ? std::vector<Expr>{x} : std::vector<Expr>{Expr()};
    });
    choose(g, p, 2,
           [&](Graph&, int c) { return std::vector<Expr>(static_cast<size_t>(c) + 1, x); });
    const std::string all = messages(g);
    INFO(all);
    CHECK(all.find("the selector must be the same on every pixel of a draw (built from constants "
                   "and parameters), but it reads varying 'x'") != std::string::npos);
    CHECK(all.find("but it reads sample") != std::string::npos);
    CHECK(all.find("the selector is a vec2, not a float") != std::string::npos);
    CHECK(all.find("0 cases is not in 1..256") != std::string::npos);
    CHECK(all.find("result 0 is a vec2 in case 1 and a float in case 0") != std::string::npos);
    CHECK(all.find("case 1 gives no result 0, others do") != std::string::npos);
    CHECK(all.find("case 1 gives 2 results, case 0 gives 1") != std::string::npos);
}

TEST_CASE("a_missing_result_can_be_filled_and_a_result_no_case_gives_stays_invalid", "[switch]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = choose(
        g, uniform(g, kSelector), 2,
        [&](Graph& body, int c) {
            return std::vector<Expr>{c == 1 ? read_in(body, x) * 3.0 : Expr(), Expr()};
        },
        [](Graph& body, size_t, Type t) {
            return t == Type::Float ? constant(body, -1.0) : Expr();
        });
    REQUIRE(r.size() == 2);
    CHECK(!r[1].valid());
    g.set_output("v", r[0].id());
    REQUIRE(g.diagnostics().empty());
    EvalInputs in;
    in.varyings["x"] = {2.0};
    in.lanes = 1;
    for (double sel : {0.0, 1.0}) {
        in.uniforms["sel"] = {sel};
        const EvalResult e = evaluate(g, "v", in, EvalPrecision::Double);
        REQUIRE(e.ok());
        CHECK(e.values[0] == (sel == 0.0 ? -1.0 : 6.0));
    }
}

TEST_CASE("the_fold_bounds_a_switch_by_its_cases_and_inlines_a_decided_one", "[switch]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = choose(g, uniform(g, kSelector), 2, [&](Graph& body, int c) {
        return std::vector<Expr>{constant(body, c == 0 ? 0.25 : 0.75) + read_in(body, x) * 0.0};
    });
    // min(r, 1) is r whichever case runs: the union of the cases' bounds is [0.25, 0.75] (x is
    // finite, so x * 0 is 0).
    FoldFacts facts;
    facts.input_ranges["x"] = {{make_interval(0.0, 1.0)}, facts.add_fact("x in [0, 1]", "")};
    g.set_output("v", min(r[0], 1.0).id());
    REQUIRE(g.diagnostics().empty());
    const FoldResult open = fold_graph(g, facts);
    CHECK(count_ops(open.graph, Op::Min) == 0);
    CHECK(count_ops(open.graph, Op::Switch) == 1);
    // A fixed selector inlines its case, which then folds like any other code.
    facts.fixed["sel"] = {{1.0}, facts.add_fact("sel = 1", "")};
    const FoldResult decided = fold_graph(g, facts);
    CHECK(count_ops(decided.graph, Op::Switch) == 0);
    const Node& out = decided.graph.node(decided.graph.outputs()[0].node);
    REQUIRE(out.op == Op::Constant);
    CHECK(out.values == std::vector<double>{0.75});
}

TEST_CASE("a_quantity_every_case_binds_is_bound_to_the_result", "[switch]") {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto both = choose(g, uniform(g, kSelector), 2, [&](Graph& body, int c) {
        return std::vector<Expr>{bind(kDoubled, read_in(body, x) * (c + 1.0))};
    });
    const auto one = choose(g, uniform(g, kSelector), 2, [&](Graph& body, int c) {
        Expr v = read_in(body, x) * (c + 3.0);
        return std::vector<Expr>{c == 0 ? bind(kDoubled, v) : v};
    });
    REQUIRE(g.diagnostics().empty());
    bool bound_both = false, bound_one = false;
    for (const auto& b : g.bindings()) {
        bound_both = bound_both || (b.quantity == kDoubled && b.node == both[0].id());
        bound_one = bound_one || (b.quantity == kDoubled && b.node == one[0].id());
    }
    CHECK(bound_both);
    CHECK_FALSE(bound_one);
}

TEST_CASE("the_fold_simplifies_inside_the_cases_of_an_undecided_switch", "[switch]") {
    // x * 0 in each case is 0 for x in [0, 1] (the switch's captured argument): each case folds
    // to its constant while the switch itself stays (the selector is not fixed).
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    const auto r = choose(g, uniform(g, kSelector), 2, [&](Graph& body, int c) {
        return std::vector<Expr>{constant(body, c == 0 ? 0.25 : 0.75) + read_in(body, x) * 0.0};
    });
    g.set_output("v", r[0].id());
    FoldFacts facts;
    facts.input_ranges["x"] = {{make_interval(0.0, 1.0)}, facts.add_fact("x in [0, 1]", "")};
    auto products = [](const Graph& folded) {
        size_t n = 0;
        for (uint32_t id : folded.live_nodes())
            if (folded.node(id).op == Op::Switch)
                for (const auto& c : folded.node(id).cases->cases)
                    n += count_ops(*c, Op::Mul);
        return n;
    };
    CHECK(products(g) == 2);
    const FoldResult open = fold_graph(g, facts);
    REQUIRE(count_ops(open.graph, Op::Switch) == 1);
    CHECK(products(open.graph) == 0);
    for (double sel : {0.0, 1.0}) {
        EvalInputs in;
        in.varyings["x"] = {0.5};
        in.lanes = 1;
        in.uniforms["sel"] = {sel};
        const EvalResult e = evaluate(open.graph, "v", in, EvalPrecision::Double);
        REQUIRE(e.ok());
        CHECK(e.values[0] == (sel == 0.0 ? 0.25 : 0.75));
    }
}
