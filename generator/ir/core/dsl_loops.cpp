// loop(): builds a loop body graph from the node author's lambda and the Loop node that runs it.
#include "watergen/ir/core/dsl.h"

#include <memory>
#include <set>
#include <utility>

#include "dsl_internal.h"

namespace watergen {

namespace {

Expr body_leaf(Graph& body, Op op, Type type, bool relaxed, size_t index) {
    Node n;
    n.op = op;
    n.type = type;
    n.relaxed = relaxed;
    if (op != Op::LoopIndex) n.values = {static_cast<double>(index)};
    return Expr(&body, body.add(std::move(n)));
}

// Whether the body's live nodes include `op`.
bool uses(const Graph& body, Op op) {
    for (uint32_t id : body.live_nodes())
        if (body.node(id).op == op) return true;
    return false;
}

// Whether `inner` is `outer` or a loop body being built inside it.
bool encloses(const Graph& outer, const Graph& inner) {
    for (const Graph* g = &inner; g; g = g->enclosing())
        if (g == &outer) return true;
    return false;
}

// The innermost of `g` and the graphs of `values`: where the loop runs.
Graph& loop_graph(Graph& g, const std::vector<Expr>& values) {
    Graph* where = &g;
    for (const Expr& e : values)
        if (e.valid() && encloses(*where, e.graph())) where = &e.graph();
    return *where;
}

// The first leaf of node `id` of `g` that is not the same for every pixel, as "varying 'v_uv'",
// or "" when there is none: parameters and constants only, followed through the captures of the
// loop bodies being built.
std::string per_pixel_leaf(const Graph& g, uint32_t id,
                           std::set<std::pair<const Graph*, uint32_t>>& seen) {
    if (!seen.insert({&g, id}).second) return "";
    const Node& n = g.node(id);
    switch (n.op) {
    case Op::Constant:
    case Op::Uniform:
        return "";
    case Op::Captured:
        if (!g.enclosing()) return "a captured value";
        return per_pixel_leaf(*g.enclosing(), g.captures()[static_cast<size_t>(n.values[0])], seen);
    case Op::Varying:
    case Op::Texture:
        return std::string(op_name(n.op)) + " '" + n.name + "'";
    case Op::LoopIndex:
    case Op::Carried:
    case Op::Loop:
    case Op::LoopResult:
        return std::string("a ") + op_name(n.op);
    default:
        for (uint32_t a : n.args)
            if (std::string leaf = per_pixel_leaf(g, a, seen); !leaf.empty()) return leaf;
        return "";
    }
}

// floor(count) in `g`, checked: a float the same for every pixel. Floored where `count` is
// computed (outside every loop it does not depend on), once. Invalid after a diagnostic.
Expr trip_count_of(Graph& g, Expr count) {
    if (count.type() == Type::Error) return Expr();
    Graph& own = count.graph();
    if (count.type() != Type::Float) {
        g.error(std::string("loop: the trip count is ") + type_name(count.type()) + ", not float");
        return Expr();
    }
    std::set<std::pair<const Graph*, uint32_t>> seen;
    if (const std::string leaf = per_pixel_leaf(own, count.id(), seen); !leaf.empty()) {
        g.error("loop: the trip count must be the same for every pixel (parameters and "
                "constants only), but it reads " +
                leaf);
        return Expr();
    }
    // Counts up to 4096 are integers binary16 cannot all hold: the count stays 32-bit.
    FullPrecisionScope full(own);
    return bring_into(named(floor(count), "trip_count"), g);
}

// The body's graph from the author's lambda, its outputs "next0".. and "continue" set; null
// after a diagnostic on `g`.
std::shared_ptr<Graph> build_body(Graph& g, LoopBody& lb, const std::vector<Expr>& init,
                                  const LoopBodyFn& body_fn) {
    auto body = std::make_shared<Graph>();
    body->begin_body(&g);
    body->set_origin(g.origin());
    body->set_relaxed(g.relaxed());
    std::vector<Expr> carried;
    for (size_t k = 0; k < init.size(); ++k) {
        const Node& n = g.node(init[k].id());
        lb.carried_types.push_back(n.type);
        lb.carried_relaxed.push_back(n.relaxed);
        carried.push_back(body_leaf(*body, Op::Carried, n.type, n.relaxed, k));
    }
    const LoopStep step = body_fn(body_leaf(*body, Op::LoopIndex, Type::Float, false, 0), carried);
    bool ok = step.next.size() == init.size();
    if (!ok)
        g.error("loop: the body returns " + std::to_string(step.next.size()) +
                " carried values for " + std::to_string(init.size()));
    for (size_t k = 0; ok && k < init.size(); ++k) {
        const Expr next = bring_into(step.next[k], *body);
        ok = next.valid() && next.type() == lb.carried_types[k];
        if (!ok && next.valid() && next.type() != Type::Error)
            g.error(std::string("loop: carried value ") + std::to_string(k) + " starts as " +
                    type_name(lb.carried_types[k]) + " and comes back as " +
                    type_name(next.type()));
        if (ok) body->set_output("next" + std::to_string(k), next.id());
    }
    if (ok && step.keep_going.valid()) {
        const Expr go = bring_into(step.keep_going, *body);
        ok = go.valid() && go.type() == Type::Bool;
        if (!ok && go.valid() && go.type() != Type::Error)
            g.error(std::string("loop: the exit condition is ") + type_name(go.type()) +
                    ", not bool");
        lb.has_exit = ok;
        if (ok) body->set_output("continue", go.id());
    }
    body->end_body();
    for (const auto& d : body->diagnostics()) {
        g.error(d.message);
        ok = false;
    }
    if (ok && (uses(*body, Op::Ddx) || uses(*body, Op::Ddy))) {
        g.error("loop: a loop body may not take ddx / ddy (undefined after a per-pixel exit)");
        ok = false;
    }
    // Implicit-LOD sampling takes derivatives too: defined in a loop every pixel runs alike.
    if (ok && lb.has_exit && uses(*body, Op::Sample)) {
        g.error("loop: a loop with an exit samples with sample_level (implicit LOD takes "
                "derivatives, undefined after a per-pixel exit)");
        ok = false;
    }
    return ok ? body : nullptr;
}

// The Loop node in `g` and one LoopResult per carried value.
std::vector<Expr> loop_results(Graph& g, std::shared_ptr<LoopBody> lb,
                               std::shared_ptr<const Graph> body, const std::vector<Expr>& init,
                               Expr count) {
    Node n;
    n.op = Op::Loop;
    n.type = Type::Tuple;
    for (const Expr& e : init)
        n.args.push_back(e.id());
    if (count.valid()) n.args.push_back(count.id());
    for (uint32_t outer : body->captures())
        n.args.push_back(outer);
    lb->body = std::move(body);
    n.loop = lb;
    const uint32_t id = g.add(std::move(n));
    std::vector<Expr> results;
    for (size_t k = 0; k < init.size(); ++k) {
        Node r;
        r.op = Op::LoopResult;
        r.type = lb->carried_types[k];
        r.relaxed = lb->carried_relaxed[k];
        r.args = {id};
        r.values = {static_cast<double>(k)};
        results.push_back(Expr(&g, g.add(std::move(r))));
    }
    return results;
}

// Both loop()s: `count` invalid for a constant trip count.
std::vector<Expr> make_loop(Graph& outer, Expr count, int trip_count,
                            const std::vector<Expr>& initial, const LoopBodyFn& body_fn,
                            LoopOptions options) {
    std::vector<Expr> placed = initial;
    placed.push_back(count);
    Graph& g = loop_graph(outer, placed);
    std::vector<Expr> init;
    for (const Expr& e : initial) {
        Expr v = bring_into(e, g);
        if (!v.valid() || v.type() == Type::Error) return std::vector<Expr>(initial.size());
        init.push_back(v);
    }
    if (trip_count < 1 || trip_count > 4096) {
        g.error("loop: " + std::string(count.valid() ? "maximum " : "") + "trip count " +
                std::to_string(trip_count) + " is not in 1..4096");
        return std::vector<Expr>(initial.size(), error_expr(g));
    }
    Expr floored;
    if (count.valid() && !(floored = trip_count_of(g, count)).valid())
        return std::vector<Expr>(initial.size(), error_expr(g));
    auto lb = std::make_shared<LoopBody>();
    lb->trip_count = trip_count;
    lb->unroll = options.unroll;
    lb->counted = floored.valid();
    std::shared_ptr<Graph> body = build_body(g, *lb, init, body_fn);
    if (!body) return std::vector<Expr>(initial.size(), error_expr(g));
    return loop_results(g, std::move(lb), std::move(body), init, floored);
}

} // namespace

std::vector<Expr> loop(Graph& g, int trip_count, const std::vector<Expr>& initial,
                       const LoopBodyFn& body_fn, LoopOptions options) {
    return make_loop(g, Expr(), trip_count, initial, body_fn, options);
}

std::vector<Expr> loop(Graph& g, Expr count, int max_trip_count, const std::vector<Expr>& initial,
                       const LoopBodyFn& body_fn, LoopOptions options) {
    if (!count.valid()) return std::vector<Expr>(initial.size()); // failed upstream, reported
    return make_loop(g, count, max_trip_count, initial, body_fn, options);
}

} // namespace watergen
