// choose(): builds the case graphs of a uniform choice from the node author's function, and the
// Switch node that runs the selected one.
#include "watergen/ir/core/dsl.h"

#include <memory>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "dsl_internal.h"

namespace watergen {

namespace {

// Whether node `id` of `g` is the same on every pixel of a draw: computed from constants and
// parameters only, following captured values out to the graphs being built around `g`. `why`
// names the first operation that is not.
bool same_on_every_pixel(const Graph& g, uint32_t id, std::string& why) {
    std::vector<std::pair<const Graph*, uint32_t>> stack{{&g, id}};
    std::set<std::pair<const Graph*, uint32_t>> seen;
    while (!stack.empty()) {
        const auto [graph, at] = stack.back();
        stack.pop_back();
        if (!seen.insert({graph, at}).second) continue;
        const Node& n = graph->node(at);
        switch (n.op) {
        case Op::Constant:
        case Op::Uniform:
            continue;
        case Op::Captured:
            if (!graph->enclosing()) break;
            stack.push_back(
                {graph->enclosing(), graph->captures()[static_cast<size_t>(n.values[0])]});
            continue;
        case Op::Varying:
        case Op::Texture:
        case Op::Sample:
        case Op::SampleLevel:
        case Op::Ddx:
        case Op::Ddy:
        case Op::Loop:
        case Op::LoopResult:
        case Op::LoopIndex:
        case Op::Carried:
        case Op::Switch:
        case Op::SwitchResult:
            break;
        default:
            for (uint32_t a : n.args)
                stack.push_back({graph, a});
            continue;
        }
        why = n.name.empty() ? op_name(n.op) : std::string(op_name(n.op)) + " '" + n.name + "'";
        return false;
    }
    return true;
}

// The outer node a case result passes through unchanged, or UINT32_MAX.
uint32_t passed_through(const Graph& body, const Expr& result) {
    const Node& n = body.node(result.id());
    if (n.op != Op::Captured) return UINT32_MAX;
    return body.captures()[static_cast<size_t>(n.values[0])];
}

// `body` again with only the results `keep` (as out0, out1, ...) and the outer values its live
// nodes read, captured in the order of first use: no case holds on to an outer value it ignores.
std::shared_ptr<Graph> rebuilt(const Graph& body, Graph& enclosing,
                               const std::vector<uint32_t>& keep) {
    std::vector<char> live(body.size(), 0);
    std::vector<uint32_t> stack(keep.begin(), keep.end());
    while (!stack.empty()) {
        const uint32_t id = stack.back();
        stack.pop_back();
        if (live[id]) continue;
        live[id] = 1;
        for (uint32_t a : body.node(id).args)
            stack.push_back(a);
    }
    auto out = std::make_shared<Graph>();
    out->begin_body(&enclosing);
    std::vector<uint32_t> map(body.size(), UINT32_MAX);
    for (uint32_t id = 0; id < body.size(); ++id) {
        if (!live[id]) continue;
        Node n = body.node(id);
        if (n.op == Op::Captured) {
            map[id] = out->capture(body.captures()[static_cast<size_t>(n.values[0])]);
            continue;
        }
        for (auto& a : n.args)
            a = map[a];
        map[id] = out->add(std::move(n));
    }
    for (size_t k = 0; k < keep.size(); ++k)
        out->set_output("out" + std::to_string(k), map[keep[k]]);
    for (const auto& b : body.bindings())
        if (map[b.node] != UINT32_MAX) out->bind(b.quantity, map[b.node]);
    out->end_body();
    return out;
}

// Whether every case binds `q` to its result k.
bool bound_in_every_case(const std::vector<std::shared_ptr<Graph>>& cases, const Quantity& q,
                         size_t k) {
    for (const auto& c : cases) {
        const uint32_t node = c->outputs()[k].node;
        bool bound = false;
        for (const auto& b : c->bindings())
            bound = bound || (b.quantity == q && b.node == node);
        if (!bound) return false;
    }
    return true;
}

// The results of every case, or an error recorded on `g` (empty return).
std::vector<std::vector<Expr>> build_cases(Graph& g, int count, const CaseFn& case_body,
                                           std::vector<std::shared_ptr<Graph>>& bodies) {
    std::vector<std::vector<Expr>> results;
    bool ok = true;
    for (int c = 0; c < count; ++c) {
        auto body = std::make_shared<Graph>();
        body->begin_body(&g);
        body->set_origin(g.origin());
        body->set_relaxed(g.relaxed());
        std::vector<Expr> r = case_body(*body, c);
        for (auto& e : r)
            if (e.valid()) e = bring_into(e, *body);
        body->end_body();
        for (const auto& d : body->diagnostics()) {
            g.error(d.message);
            ok = false;
        }
        if (!results.empty() && r.size() != results.front().size()) {
            g.error(fmt::format("choose: case {} gives {} results, case 0 gives {}", c, r.size(),
                                results.front().size()));
            ok = false;
        }
        bodies.push_back(std::move(body));
        results.push_back(std::move(r));
    }
    if (!ok) results.clear();
    return results;
}

// Gives result k in every case that lacks it (a result some cases give), with fill_missing.
void fill_in(Graph& g, std::vector<std::shared_ptr<Graph>>& bodies,
             std::vector<std::vector<Expr>>& results, size_t k, const FillFn& fill_missing) {
    Type type = Type::Error;
    for (const auto& r : results)
        if (r[k].valid()) type = r[k].type();
    if (type == Type::Error || !fill_missing) return;
    for (size_t c = 0; c < results.size(); ++c) {
        if (results[c][k].valid()) continue;
        Graph& body = *bodies[c];
        body.begin_body(&g);
        const Expr e = fill_missing(body, k, type);
        results[c][k] = e.valid() ? bring_into(e, body) : e;
        body.end_body();
    }
}

// The Switch node over the cases (rebuilt with the results `kept` only) and its results, written
// into `out`; quantities every case binds to a result are bound to it.
void add_switch(Graph& g, const Expr& sel, const std::vector<std::shared_ptr<Graph>>& bodies,
                const std::vector<std::vector<Expr>>& results, const std::vector<size_t>& kept,
                std::vector<Expr>& out) {
    Node sw;
    sw.op = Op::Switch;
    sw.type = Type::Tuple;
    sw.args = {sel.id()};
    auto cases = std::make_shared<SwitchCases>();
    std::vector<std::shared_ptr<Graph>> compact;
    for (size_t c = 0; c < bodies.size(); ++c) {
        std::vector<uint32_t> keep;
        for (size_t k : kept)
            keep.push_back(results[c][k].id());
        compact.push_back(rebuilt(*bodies[c], g, keep));
        cases->case_args.push_back(sw.args.size());
        for (uint32_t outer : compact.back()->captures())
            sw.args.push_back(outer);
        cases->cases.push_back(compact.back());
    }
    for (size_t j = 0; j < kept.size(); ++j) {
        cases->result_types.push_back(results[0][kept[j]].type());
        bool relaxed = true; // relaxed only if every case's value is: no value is ever narrowed
        for (const auto& c : compact)
            relaxed = relaxed && c->node(c->outputs()[j].node).relaxed;
        cases->result_relaxed.push_back(relaxed);
    }
    sw.cases = cases;
    const uint32_t id = g.add(std::move(sw));
    for (size_t j = 0; j < kept.size(); ++j) {
        Node r;
        r.op = Op::SwitchResult;
        r.type = cases->result_types[j];
        r.relaxed = cases->result_relaxed[j];
        r.args = {id};
        r.values = {static_cast<double>(j)};
        out[kept[j]] = Expr(&g, g.add(std::move(r)));
        for (const auto& b : compact[0]->bindings())
            if (b.node == compact[0]->outputs()[j].node &&
                bound_in_every_case(compact, b.quantity, j))
                g.bind(b.quantity, out[kept[j]].id());
    }
}

} // namespace

Expr read_in(Graph& body, Expr outer) {
    return bring_into(outer, body);
}

std::vector<Expr> choose(Graph& g, Expr selector, int count, const CaseFn& case_body,
                         const FillFn& fill_missing) {
    const Expr sel = bring_into(selector, g);
    if (!sel.valid() || sel.type() == Type::Error) return {};
    std::string why;
    if (sel.type() != Type::Float) {
        g.error(std::string("choose: the selector is a ") + type_name(sel.type()) +
                ", not a float");
        return {};
    }
    if (count < 1 || count > 256) {
        g.error(fmt::format("choose: {} cases is not in 1..256", count));
        return {};
    }
    if (!same_on_every_pixel(g, sel.id(), why)) {
        g.error("choose: the selector must be the same on every pixel of a draw (built from "
                "constants and parameters), but it reads " +
                why);
        return {};
    }
    std::vector<std::shared_ptr<Graph>> bodies;
    std::vector<std::vector<Expr>> results = build_cases(g, count, case_body, bodies);
    if (results.empty()) return {};
    const size_t n = results.front().size();
    std::vector<Expr> out(n);
    std::vector<size_t> kept; // results that need the switch
    for (size_t k = 0; k < n; ++k) {
        fill_in(g, bodies, results, k, fill_missing);
        size_t given = 0;
        for (const auto& r : results)
            given += r[k].valid() ? 1 : 0;
        if (given == 0) continue;
        for (size_t c = 0; c < results.size(); ++c) {
            const Expr& e = results[c][k];
            if (e.valid() && e.type() == results.front()[k].type()) continue;
            g.error(!e.valid() ? fmt::format("choose: case {} gives no result {}, others do", c, k)
                               : fmt::format("choose: result {} is a {} in case {} and a {} in "
                                             "case 0",
                                             k, type_name(e.type()), c,
                                             type_name(results.front()[k].type())));
            return std::vector<Expr>(n, error_expr(g));
        }
        const uint32_t through = passed_through(*bodies[0], results[0][k]);
        bool same = through != UINT32_MAX;
        for (size_t c = 1; same && c < results.size(); ++c)
            same = passed_through(*bodies[c], results[c][k]) == through;
        if (same)
            out[k] = Expr(&g, through);
        else
            kept.push_back(k);
    }
    if (kept.empty()) return out;

    add_switch(g, sel, bodies, results, kept, out);
    return out;
}

} // namespace watergen
