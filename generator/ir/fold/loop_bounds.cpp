// Bounds of what a loop computes, for the fold pass: the body's interval analysis run over the
// iterations (the loop unrolled for analysis only), widened where a bound keeps moving.
#include <cmath>
#include <limits>

#include "folder.h"

namespace watergen::fold {

namespace {

// This many iterations are followed step by step: a loop without an exit ends in the state after
// exactly the last one; a loop with an exit in the union of the states after each. Past this
// count a bound still moving is widened (widened()), for at most kMaxRounds rounds.
constexpr int kStepByStep = 64;
constexpr int kMaxRounds = 256;
constexpr int kNarrowingSteps = 8;

Interval hull(const Interval& a, const Interval& b) {
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi), a.finite && b.finite};
}

bool same(const Interval& a, const Interval& b) {
    return a.lo == b.lo && a.hi == b.hi && a.finite == b.finite;
}

// A bound that moved from `before` to `after`, pushed out to the next threshold: 16 |b| + 1
// past the new bound, infinity beyond the largest float.
Interval widened(const Interval& before, Interval after) {
    const double inf = std::numeric_limits<double>::infinity();
    auto push = [&](double b) { return std::fabs(b) * 16.0 + 1.0; };
    if (after.lo < before.lo) after.lo = after.lo - push(after.lo);
    if (after.hi > before.hi) after.hi = after.hi + push(after.hi);
    if (after.lo < -3.5e38) after.lo = -inf;
    if (after.hi > 3.5e38) after.hi = inf;
    after.finite = after.finite && std::isfinite(after.lo) && std::isfinite(after.hi);
    return after;
}

// The bounds of carried value k within a Loop node's bounds (its carried values side by side).
Intervals slice(const LoopBody& loop, const Intervals& all, size_t k) {
    size_t offset = 0;
    for (size_t j = 0; j < k; ++j)
        offset += static_cast<size_t>(component_count(loop.carried_types[j]));
    const size_t comps = static_cast<size_t>(component_count(loop.carried_types[k]));
    if (all.size() < offset + comps) return unknown_intervals(loop.carried_types[k], false);
    return Intervals(all.begin() + static_cast<long>(offset),
                     all.begin() + static_cast<long>(offset + comps));
}

// A Loop node's argument bounds apart: the carried values' initial ones, the captured ones.
std::pair<std::vector<Intervals>, std::vector<const Intervals*>>
split_arguments(const LoopBody& loop, const std::vector<const Intervals*>& args) {
    std::vector<Intervals> initial(loop.carried());
    for (size_t k = 0; k < loop.carried(); ++k)
        initial[k] = *args[k];
    return {std::move(initial),
            std::vector<const Intervals*>(args.begin() + static_cast<long>(loop.first_capture()),
                                          args.end())};
}

} // namespace

Intervals Folder::loop_result_bounds(const Node& result, const Node& loop_node,
                                     const Intervals& loop_bounds) {
    return slice(*loop_node.loop, loop_bounds, static_cast<size_t>(result.values[0]));
}

// One pass over the body from the carried values' bounds at an iteration's start: the bounds
// of their next values. Leaves: the iteration in [0, trips - 1], the captured values' bounds,
// parameters and inputs by the scene's facts as outside.
std::pair<Folder::State, FactSet>
Folder::body_step(const LoopBody& loop, const BodyScratch& scratch, const State& carried,
                  const std::vector<const Intervals*>& captured) const {
    const Graph& body = *loop.body;
    std::vector<Intervals>& v = scratch.values;
    FactSet facts;
    for (uint32_t id : scratch.live) {
        const Node& n = body.node(id);
        const size_t index = n.values.empty() ? 0 : static_cast<size_t>(n.values[0]);
        if (n.op == Op::LoopIndex) {
            v[id] = {make_interval(0.0, loop.trip_count - 1.0)};
        } else if (n.op == Op::Carried) {
            v[id] = carried[index];
        } else if (n.op == Op::Captured) {
            v[id] = *captured[index];
        } else if (n.op == Op::Uniform || n.op == Op::UniformElement || n.op == Op::Varying ||
                   n.op == Op::Sample || n.op == Op::SampleLevel) {
            auto [b, f] = leaf_bounds(body, n, id);
            v[id] = std::move(b);
            facts |= f;
        } else if (n.op == Op::LoopResult) {
            const Node& inner = body.node(n.args[0]);
            v[id] = slice(*inner.loop, v[n.args[0]], index);
        } else {
            std::vector<const Intervals*> args;
            std::vector<Type> types;
            for (uint32_t a : n.args) {
                args.push_back(&v[a]);
                types.push_back(body.node(a).type);
            }
            if (n.op == Op::Loop) {
                auto [b, f] = loop_bounds(n, args);
                v[id] = std::move(b);
                facts |= f;
            } else {
                v[id] = node_intervals(n, args, types);
            }
        }
    }
    State next(loop.carried());
    for (size_t k = 0; k < loop.carried(); ++k) {
        const uint32_t out = scratch.next[k];
        next[k] = out < v.size() && !v[out].empty()
                      ? v[out]
                      : unknown_intervals(loop.carried_types[k], false);
    }
    return {std::move(next), facts};
}

Folder::BodyScratch Folder::scratch_for(const LoopBody& loop) {
    BodyScratch scratch;
    scratch.live = loop.body->live_nodes();
    scratch.values.resize(loop.body->size());
    scratch.next.assign(loop.carried(), UINT32_MAX);
    for (const auto& o : loop.body->outputs())
        for (size_t k = 0; k < loop.carried(); ++k)
            if (o.name == "next" + std::to_string(k)) scratch.next[k] = o.node;
    return scratch;
}

std::optional<Folder::State> Folder::carried_hull(const LoopBody& loop, const BodyScratch& scratch,
                                                  const State& initial,
                                                  const std::vector<const Intervals*>& captured,
                                                  FactSet& facts) const {
    // Few iterations: the hull of the states before each, followed step by step.
    if (loop.trip_count <= kStepByStep) {
        State hulled = initial, at = initial;
        for (int i = 0; i + 1 < loop.trip_count; ++i) {
            auto [next, f] = body_step(loop, scratch, at, captured);
            facts |= f;
            at = std::move(next);
            for (size_t k = 0; k < hulled.size(); ++k)
                for (size_t c = 0; c < hulled[k].size() && c < at[k].size(); ++c)
                    hulled[k][c] = hull(hulled[k][c], at[k][c]);
        }
        return hulled;
    }
    // Else the union of every state, as loop_bounds() finds it for a loop that may stop early.
    bool settled = false;
    return union_of_states(loop, scratch, initial, captured, facts, settled);
}

std::optional<Folder::State> Folder::union_of_states(const LoopBody& loop,
                                                     const BodyScratch& scratch, State state,
                                                     const std::vector<const Intervals*>& captured,
                                                     FactSet& facts, bool& settled) const {
    settled = false;
    for (int round = 0; round < kMaxRounds; ++round) {
        if (round >= loop.trip_count) return state;
        auto [next, f] = body_step(loop, scratch, state, captured);
        facts |= f;
        bool moved = false;
        for (size_t k = 0; k < state.size(); ++k)
            for (size_t c = 0; c < state[k].size() && c < next[k].size(); ++c) {
                Interval u = hull(state[k][c], next[k][c]);
                if (same(u, state[k][c])) continue;
                moved = true;
                if (round >= kStepByStep) u = widened(state[k][c], u);
                state[k][c] = u;
            }
        if (moved) continue;
        settled = true;
        return state;
    }
    return std::nullopt;
}

std::shared_ptr<const LoopBody> Folder::fold_body(const Node& n) const {
    const LoopBody& loop = *n.loop;
    std::vector<const Intervals*> args;
    for (uint32_t a : n.args)
        args.push_back(&values_[a]);
    const auto [initial, captured] = split_arguments(loop, args);
    const BodyScratch scratch = scratch_for(loop);
    FactSet facts;
    const std::optional<State> carried = carried_hull(loop, scratch, initial, captured, facts);
    if (!carried) return n.loop;
    // What every iteration may see.
    std::map<uint32_t, Intervals> leaves;
    const Graph& body = *loop.body;
    for (uint32_t id : scratch.live) {
        const Node& b = body.node(id);
        const size_t index = b.values.empty() ? 0 : static_cast<size_t>(b.values[0]);
        if (b.op == Op::LoopIndex)
            leaves[id] = {make_interval(0.0, loop.trip_count - 1.0)};
        else if (b.op == Op::Carried && index < carried->size())
            leaves[id] = (*carried)[index];
        else if (b.op == Op::Captured && index < captured.size())
            leaves[id] = *captured[index];
    }
    std::optional<Graph> folded_body = fold_inner(body, std::move(leaves), "the loop's bounds");
    if (!folded_body) return n.loop;
    auto folded = std::make_shared<LoopBody>(loop);
    folded->body = std::make_shared<const Graph>(std::move(*folded_body));
    return folded;
}

std::optional<Graph> Folder::fold_inner(const Graph& inner, std::map<uint32_t, Intervals> leaves,
                                        const char* bounded_by) const {
    // The inner graph's own events are not reported, so one fact names what bounds its leaves.
    FoldFacts facts = f_;
    const size_t fact = facts.add_fact(bounded_by, "");
    std::map<uint32_t, FoldFacts::Bounds> bounds;
    for (auto& [id, v] : leaves)
        bounds[id] = {std::move(v), fact};
    Folder folder(inner, declarations_, facts, std::move(bounds));
    folder.rewrite_all();
    if (folder.events().empty()) return std::nullopt;
    return compact(folder.out_);
}

// The bounds of a Loop node (its carried values side by side) from its arguments' bounds: the
// initial values, then the captured ones.
std::pair<Intervals, FactSet> Folder::loop_bounds(const Node& n,
                                                  const std::vector<const Intervals*>& args) const {
    const LoopBody& loop = *n.loop;
    auto [state, captured] = split_arguments(loop, args);
    const BodyScratch scratch = scratch_for(loop);
    FactSet facts;
    auto flatten = [&](const State& s) {
        Intervals all;
        for (const auto& c : s)
            all.insert(all.end(), c.begin(), c.end());
        return std::pair<Intervals, FactSet>{std::move(all), facts};
    };
    // A loop that may stop early (an exit, or a trip count from data) ends in any state.
    if (!loop.has_exit && !loop.counted && loop.trip_count <= kStepByStep) {
        for (int i = 0; i < loop.trip_count; ++i) {
            auto [next, f] = body_step(loop, scratch, state, captured);
            state = std::move(next);
            facts |= f;
        }
        return flatten(state);
    }
    // The union of the states after 0, 1, ... iterations: U = U u f(U) until nothing moves,
    // or every iteration is accounted for. A bound still moving after a while is widened to a
    // threshold (16 |b| + 1, then on to infinity); once nothing moves, U holds every state, and
    // so does init u f(U), which narrows the widened bounds back down.
    const State initial = state;
    bool settled = false;
    std::optional<State> all = union_of_states(loop, scratch, state, captured, facts, settled);
    if (!all) {
        State unknown(loop.carried());
        for (size_t k = 0; k < loop.carried(); ++k)
            unknown[k] = unknown_intervals(loop.carried_types[k], false);
        return flatten(unknown);
    }
    state = std::move(*all);
    if (settled)
        for (int i = 0; i < kNarrowingSteps; ++i) {
            auto [narrower, g] = body_step(loop, scratch, state, captured);
            facts |= g;
            for (size_t k = 0; k < state.size(); ++k)
                for (size_t c = 0; c < state[k].size() && c < narrower[k].size(); ++c)
                    state[k][c] = hull(initial[k][c], narrower[k][c]);
        }
    return flatten(state);
}

} // namespace watergen::fold
