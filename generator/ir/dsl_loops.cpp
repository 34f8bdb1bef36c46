// loop(): builds a loop body graph from the node author's lambda and the Loop node that runs it.
#include "watergen/ir/dsl.h"

#include <memory>

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

} // namespace

std::vector<Expr> loop(Graph& g, int trip_count, const std::vector<Expr>& initial,
                       const LoopBodyFn& body_fn, LoopOptions options) {
    std::vector<Expr> init;
    for (const Expr& e : initial) {
        Expr v = bring_into(e, g);
        if (!v.valid() || v.type() == Type::Error) return std::vector<Expr>(initial.size());
        init.push_back(v);
    }
    if (trip_count < 1 || trip_count > 4096) {
        g.error("loop: trip count " + std::to_string(trip_count) + " is not in 1..4096");
        return std::vector<Expr>(initial.size(), error_expr(g));
    }
    auto body = std::make_shared<Graph>();
    body->begin_body(&g);
    body->set_origin(g.origin());
    body->set_relaxed(g.relaxed());
    auto lb = std::make_shared<LoopBody>();
    lb->trip_count = trip_count;
    lb->unroll = options.unroll;
    std::vector<Expr> carried;
    for (size_t k = 0; k < init.size(); ++k) {
        const Node& n = g.node(init[k].id());
        lb->carried_types.push_back(n.type);
        lb->carried_relaxed.push_back(n.relaxed);
        carried.push_back(body_leaf(*body, Op::Carried, n.type, n.relaxed, k));
    }
    const LoopStep step = body_fn(body_leaf(*body, Op::LoopIndex, Type::Float, false, 0), carried);
    bool ok = step.next.size() == init.size();
    if (!ok)
        g.error("loop: the body returns " + std::to_string(step.next.size()) +
                " carried values for " + std::to_string(init.size()));
    for (size_t k = 0; ok && k < init.size(); ++k) {
        const Expr next = bring_into(step.next[k], *body);
        ok = next.valid() && next.type() == lb->carried_types[k];
        if (!ok && next.valid() && next.type() != Type::Error)
            g.error(std::string("loop: carried value ") + std::to_string(k) + " starts as " +
                    type_name(lb->carried_types[k]) + " and comes back as " +
                    type_name(next.type()));
        if (ok) body->set_output("next" + std::to_string(k), next.id());
    }
    if (ok && step.keep_going.valid()) {
        const Expr go = bring_into(step.keep_going, *body);
        ok = go.valid() && go.type() == Type::Bool;
        if (!ok && go.valid() && go.type() != Type::Error)
            g.error(std::string("loop: the exit condition is ") + type_name(go.type()) +
                    ", not bool");
        lb->has_exit = ok;
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
    if (ok && lb->has_exit && uses(*body, Op::Sample)) {
        g.error("loop: a loop with an exit samples with sample_level (implicit LOD takes "
                "derivatives, undefined after a per-pixel exit)");
        ok = false;
    }
    if (!ok) return std::vector<Expr>(initial.size(), error_expr(g));

    Node n;
    n.op = Op::Loop;
    n.type = Type::Tuple;
    for (const Expr& e : init)
        n.args.push_back(e.id());
    for (uint32_t outer : body->captures())
        n.args.push_back(outer);
    lb->body = body;
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

} // namespace watergen
