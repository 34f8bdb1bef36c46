// The fold pass's rewrite rules: bounds of each node, constants by evaluation and by bounds,
// the algebraic identities (ir_fold.h lists them).
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "folder.h"
#include "watergen/ir/core/op_table.h"
#include "watergen/ir/core/shader_values.h"
#include "watergen/ir/core/text.h"
#include "watergen/ir/cpu/cpu_evaluator.h"

namespace watergen::fold {

namespace {

bool is_float_valued(Type t) {
    return is_float_numeric(t) || t == Type::Mat3;
}

// Whether a node of constant operands is itself a constant: its value is a function of its
// operands' values alone (a loop's too: its body is part of it; a switch's cases are graphs of
// their own).
bool pure(Op op) {
    const OpKind k = op_info(op).kind;
    return (k == OpKind::Math || k == OpKind::Control || k == OpKind::BodyInput) &&
           op != Op::Switch;
}

// Evaluates one operation on constant arguments with the CPU evaluator, so folding and the
// reference evaluation agree by construction.
std::optional<std::vector<double>> evaluate_constant(const Node& n,
                                                     const std::vector<const Node*>& args) {
    Graph g;
    Node op = n;
    op.args.clear();
    op.name.clear();
    for (const Node* a : args) {
        Node c;
        c.op = Op::Constant;
        c.type = a->type;
        c.values = a->values;
        op.args.push_back(g.add(std::move(c)));
    }
    g.set_output("v", g.add(std::move(op)));
    EvalInputs in;
    in.lanes = 1;
    const EvalResult r = evaluate(g, "v", in, EvalPrecision::Double);
    if (!r.ok()) return std::nullopt;
    for (double v : r.values)
        if (!std::isfinite(v)) return std::nullopt;
    return r.values;
}

} // namespace

std::string label(const Node& n) {
    if (!n.name.empty() && n.op != Op::Constant) return n.name;
    if (is_infix(n.op)) return std::string("(... ") + op_name(n.op) + " ...)";
    return std::string(op_name(n.op)) + "(...)";
}

// Adds `n` to the output graph with its bounds and the facts behind them.
uint32_t Folder::emit(Node n, Intervals v, FactSet facts) {
    const uint32_t id = out_.add(std::move(n));
    if (id >= values_.size()) {
        values_.resize(id + 1);
        facts_.resize(id + 1);
        values_[id] = std::move(v);
        facts_[id] = facts;
    } else if (values_[id].size() == v.size()) {
        // The same value reached another way (a name is no part of node identity): both
        // bounds hold, so keep their intersection (when they overlap, as they must).
        bool overlap = true;
        for (size_t c = 0; c < v.size(); ++c)
            overlap = overlap &&
                      std::max(values_[id][c].lo, v[c].lo) <= std::min(values_[id][c].hi, v[c].hi);
        for (size_t c = 0; overlap && c < v.size(); ++c) {
            Interval& e = values_[id][c];
            e.lo = std::max(e.lo, v[c].lo);
            e.hi = std::min(e.hi, v[c].hi);
            e.finite = e.finite || v[c].finite;
        }
        if (overlap) facts_[id] |= facts;
    }
    return id;
}

uint32_t Folder::constant(const Node& like, std::vector<double> values, FactSet facts) {
    Node c;
    c.op = Op::Constant;
    c.type = like.type;
    c.values = std::move(values);
    c.origin = like.origin;
    c.relaxed = like.relaxed;
    Intervals v;
    for (double x : c.values)
        v.push_back(make_interval(x, x));
    return emit(std::move(c), std::move(v), facts);
}

void Folder::event(uint32_t in_id, std::string what, FactSet facts) {
    event_of_[in_id] = static_cast<int>(report_.events.size());
    report_.events.push_back({in_id, in_.node(in_id).origin, std::move(what), facts});
}

Intervals Folder::bounds_of(const FoldFacts::Bounds& b, Type t) const {
    const size_t comps = static_cast<size_t>(component_count(t));
    if (b.bounds.size() == comps) return b.bounds;
    return Intervals(comps, b.bounds.empty() ? Interval{} : b.bounds[0]);
}

FactSet Folder::single(size_t fact) const {
    FactSet s;
    s.set(std::min(fact, kMaxFacts - 1));
    return s;
}

// Bounds and facts of a leaf read.
std::pair<Intervals, FactSet> Folder::leaf_bounds(const Graph& g, const Node& n,
                                                  uint32_t id) const {
    // An array element: every element lies in the parameter's range.
    if (n.op == Op::Uniform || n.op == Op::UniformElement) {
        // A value the host computes or moves into the frame (ir/core/shader_values.h) ranges
        // as its rule says; of the facts on the value as set, only a frame point's height
        // (its y, which the frame keeps) still holds.
        if (const Parameter* p = declarations_.find_parameter(n.name);
            p && p->host.rule != HostRule::Given) {
            Intervals v;
            for (const auto& [lo, hi] : host_value_range(*p))
                v.push_back(make_interval(lo, hi));
            FactSet facts;
            if (auto it = f_.parameter_ranges.find(n.name); it != f_.parameter_ranges.end() &&
                                                            p->host.rule == HostRule::FramePoint &&
                                                            v.size() == 3) {
                const Intervals given = bounds_of(it->second, n.type);
                if (given.size() == 3) {
                    v[1] = given[1];
                    facts = single(it->second.fact);
                }
            }
            if (v.size() == static_cast<size_t>(component_count(n.type))) return {v, facts};
        }
        if (auto it = f_.parameter_ranges.find(n.name); it != f_.parameter_ranges.end())
            return {bounds_of(it->second, n.type), single(it->second.fact)};
        if (const Parameter* p = declarations_.find_parameter(n.name))
            return {Intervals(static_cast<size_t>(component_count(n.type)),
                              make_interval(p->min, p->max)),
                    {}};
        return {unknown_intervals(n.type, false), {}};
    }
    // Varyings and samples: the scene's input contract; unknown inputs are assumed finite.
    std::string name = n.name;
    if (n.op == Op::Sample || n.op == Op::SampleLevel) name = g.node(g.node(id).args[0]).name;
    if (auto it = f_.input_ranges.find(name); it != f_.input_ranges.end())
        return {bounds_of(it->second, n.type), single(it->second.fact)};
    return {unknown_intervals(n.type, true), {}};
}

bool Folder::is_constant(uint32_t id, double x) const {
    const Node& n = out_.node(id);
    if (n.op != Op::Constant || n.values.empty()) return false;
    for (double v : n.values)
        if (v != x) return false;
    return true;
}

bool Folder::all_finite(uint32_t id) const {
    for (const auto& v : values_[id])
        if (!v.finite) return false;
    return true;
}

// `id` standing in for a node of type `t`: scalars widen by a splat.
std::optional<uint32_t> Folder::as_type(uint32_t id, const Node& like) {
    const Type t = out_.node(id).type;
    if (t == like.type) return id;
    if (t != Type::Float || !is_vector(like.type)) return std::nullopt;
    Node s;
    s.op = Op::Splat;
    s.type = like.type;
    s.args = {id};
    s.origin = like.origin;
    s.relaxed = like.relaxed;
    Intervals v(static_cast<size_t>(component_count(like.type)), values_[id][0]);
    return emit(std::move(s), std::move(v), facts_[id]);
}

// Each component of a is >= the matching (or broadcast) component of b.
bool Folder::all_ge(const Intervals& a, const Intervals& b) const {
    const size_t n = std::max(a.size(), b.size());
    for (size_t c = 0; c < n; ++c) {
        const Interval& x = a.size() == 1 ? a[0] : a[c];
        const Interval& y = b.size() == 1 ? b[0] : b[c];
        if (!x.finite || !y.finite || !(x.lo >= y.hi)) return false;
    }
    return true;
}

std::optional<uint32_t> Folder::identity(const Node& n, uint32_t in_id, const FactSet& all_facts) {
    const auto& a = n.args;
    auto take = [&](uint32_t arg, const std::string& what,
                    FactSet facts) -> std::optional<uint32_t> {
        auto r = as_type(arg, n);
        if (r) event(in_id, label(in_.node(in_id)) + ": " + what, facts);
        return r;
    };
    switch (n.op) {
    case Op::Add:
        if (is_constant(a[1], 0.0)) return take(a[0], "x + 0 -> x", facts_[a[1]]);
        if (is_constant(a[0], 0.0)) return take(a[1], "0 + x -> x", facts_[a[0]]);
        break;
    case Op::Sub:
        if (is_constant(a[1], 0.0)) return take(a[0], "x - 0 -> x", facts_[a[1]]);
        if (is_constant(a[0], 0.0) && out_.node(a[1]).type == n.type) {
            Node neg;
            neg.op = Op::Neg;
            neg.type = n.type;
            neg.args = {a[1]};
            neg.origin = n.origin;
            neg.relaxed = n.relaxed;
            event(in_id, label(in_.node(in_id)) + ": 0 - x -> -x", facts_[a[0]]);
            Intervals v;
            for (const auto& c : values_[a[1]])
                v.push_back({-c.hi, -c.lo, c.finite});
            return emit(std::move(neg), std::move(v), facts_[a[0]] | facts_[a[1]]);
        }
        break;
    case Op::Mul:
        if (is_constant(a[1], 1.0)) return take(a[0], "x * 1 -> x", facts_[a[1]]);
        if (is_constant(a[0], 1.0)) return take(a[1], "1 * x -> x", facts_[a[0]]);
        for (int z = 0; z < 2; ++z)
            if (is_constant(a[z], 0.0) && all_finite(a[1 - z])) {
                event(in_id, label(in_.node(in_id)) + ": x * 0 -> 0 (x is finite)", facts_[a[z]]);
                return constant(
                    n, std::vector<double>(static_cast<size_t>(component_count(n.type)), 0.0),
                    facts_[a[z]]);
            }
        break;
    case Op::Div:
        if (is_constant(a[1], 1.0)) return take(a[0], "x / 1 -> x", facts_[a[1]]);
        break;
    case Op::Neg:
        if (out_.node(a[0]).op == Op::Neg) return take(out_.node(a[0]).args[0], "-(-x) -> x", {});
        break;
    case Op::Mix:
        if (is_constant(a[2], 0.0)) return take(a[0], "mix(a, b, 0) -> a", facts_[a[2]]);
        if (is_constant(a[2], 1.0)) return take(a[1], "mix(a, b, 1) -> b", facts_[a[2]]);
        if (a[0] == a[1]) return take(a[0], "mix(a, a, t) -> a", {});
        break;
    case Op::Select:
        if (decided_true(values_[a[0]])) return take(a[1], "select(true, a, b) -> a", facts_[a[0]]);
        if (decided_false(values_[a[0]]))
            return take(a[2], "select(false, a, b) -> b", facts_[a[0]]);
        if (a[1] == a[2]) return take(a[1], "select(c, a, a) -> a", {});
        break;
    case Op::Max:
        if (all_ge(values_[a[0]], values_[a[1]]))
            return take(a[0], "max(a, b) -> a (a >= b)", all_facts);
        if (all_ge(values_[a[1]], values_[a[0]]))
            return take(a[1], "max(a, b) -> b (b >= a)", all_facts);
        break;
    case Op::Min:
        if (all_ge(values_[a[1]], values_[a[0]]))
            return take(a[0], "min(a, b) -> a (a <= b)", all_facts);
        if (all_ge(values_[a[0]], values_[a[1]]))
            return take(a[1], "min(a, b) -> b (b <= a)", all_facts);
        break;
    case Op::Clamp:
        if (all_ge(values_[a[0]], values_[a[1]]) && all_ge(values_[a[2]], values_[a[0]]))
            return take(a[0], "clamp(x, lo, hi) -> x (x within)", all_facts);
        break;
    case Op::Saturate: {
        const Intervals zero{make_interval(0.0, 0.0)}, one{make_interval(1.0, 1.0)};
        if (all_ge(values_[a[0]], zero) && all_ge(one, values_[a[0]]))
            return take(a[0], "saturate(x) -> x (x within [0, 1])", all_facts);
        break;
    }
    case Op::Pow:
        if (is_constant(a[1], 1.0)) return take(a[0], "pow(x, 1) -> x", facts_[a[1]]);
        break;
    default:
        break;
    }
    return std::nullopt;
}

// The bounds of `n` (arguments already rewritten) and the facts behind them.
std::pair<Intervals, FactSet> Folder::bounds(const Node& n, uint32_t in_id) const {
    if (n.op == Op::Uniform || n.op == Op::UniformElement || n.op == Op::Varying ||
        n.op == Op::Sample || n.op == Op::SampleLevel)
        return leaf_bounds(in_, in_.node(in_id), in_id);
    // A switch result: from the switch's arguments, through its cases.
    const Node& from = n.op == Op::SwitchResult ? out_.node(n.args[0]) : n;
    FactSet facts;
    std::vector<const Intervals*> args;
    std::vector<Type> types;
    for (uint32_t a : from.args) {
        args.push_back(&values_[a]);
        types.push_back(out_.node(a).type);
        facts |= facts_[a];
    }
    if (n.op == Op::Loop) {
        auto [v, loop_facts] = loop_bounds(n, args);
        return {std::move(v), facts | loop_facts};
    }
    if (n.op == Op::LoopResult)
        return {loop_result_bounds(n, out_.node(n.args[0]), values_[n.args[0]]), facts};
    if (n.op == Op::SwitchResult)
        return {switch_result_intervals(from, static_cast<size_t>(n.values[0]), args), facts};
    return {node_intervals(n, args, types), facts};
}

// Narrows `v` by what the facts assume of the quantity bound to node `in_id`, if any.
void Folder::narrow_by_assumption(uint32_t in_id, Type t, Intervals& v, FactSet& facts) const {
    auto it = node_ranges_.find(in_id);
    if (it == node_ranges_.end()) return;
    // An assumption the computed bounds contradict cannot hold anywhere; ignore it
    // rather than fold by an empty range.
    const Intervals assumed = bounds_of(it->second, t);
    bool consistent = assumed.size() == v.size();
    for (size_t c = 0; consistent && c < v.size(); ++c)
        consistent = std::max(v[c].lo, assumed[c].lo) <= std::min(v[c].hi, assumed[c].hi);
    for (size_t c = 0; consistent && c < v.size(); ++c) {
        v[c].lo = std::max(v[c].lo, assumed[c].lo);
        v[c].hi = std::min(v[c].hi, assumed[c].hi);
        v[c].finite = v[c].finite || (std::isfinite(v[c].lo) && std::isfinite(v[c].hi));
    }
    if (consistent) facts.set(std::min(it->second.fact, kMaxFacts - 1));
}

// A float value computed from constants, or pinned down (or to within +-vanish) by its bounds.
std::optional<uint32_t> Folder::fold_to_constant(const Node& n, uint32_t in_id, const Intervals& v,
                                                 const FactSet& facts) {
    // Constant arguments only: evaluate.
    bool constant_args = pure(n.op) && !n.args.empty();
    std::vector<const Node*> arg_nodes;
    for (uint32_t a : n.args) {
        constant_args = constant_args && out_.node(a).op == Op::Constant;
        arg_nodes.push_back(&out_.node(a));
    }
    if (constant_args)
        if (auto value = evaluate_constant(n, arg_nodes)) {
            if (facts.any())
                event(in_id, label(in_.node(in_id)) + " of constants -> " + spell_values(*value),
                      facts);
            return constant(n, std::move(*value), facts);
        }
    // Bounds that pin the value down.
    bool point = !v.empty(), vanishing = !v.empty(), zero = true;
    for (const auto& c : v) {
        point = point && c.is_point();
        vanishing =
            vanishing && c.finite && std::fabs(c.lo) <= f_.vanish && std::fabs(c.hi) <= f_.vanish;
        zero = zero && c.lo == 0.0 && c.hi == 0.0;
    }
    if (point) {
        std::vector<double> values;
        for (const auto& c : v)
            values.push_back(c.lo);
        event(in_id, label(in_.node(in_id)) + " is always " + spell_values(values), facts);
        return constant(n, std::move(values), facts);
    }
    if (vanishing && !zero) {
        double bound = 0.0;
        for (const auto& c : v)
            bound = std::max({bound, std::fabs(c.lo), std::fabs(c.hi)});
        event(in_id,
              label(in_.node(in_id)) + fmt::format(" vanishes (|value| <= {:.2g}) -> 0", bound),
              facts);
        return constant(n, std::vector<double>(v.size(), 0.0), facts);
    }
    return std::nullopt;
}

uint32_t Folder::rewrite(uint32_t in_id) {
    Node n = in_.node(in_id);
    for (auto& a : n.args)
        a = map_[a];

    // A value the host computes or moves (shader_values.h) is not the value fixed: it stays.
    const Parameter* declared =
        n.op == Op::Uniform ? declarations_.find_parameter(n.name) : nullptr;
    if (n.op == Op::Uniform && !(declared && declared->host.rule != HostRule::Given)) {
        if (auto it = f_.fixed.find(n.name);
            it != f_.fixed.end() &&
            it->second.value.size() == static_cast<size_t>(component_count(n.type))) {
            report_.folded_parameters[n.name] = it->second.value;
            event(in_id, n.name + " is fixed to " + spell_values(it->second.value),
                  single(it->second.fact));
            return constant(n, it->second.value, single(it->second.fact));
        }
    }

    if (n.op == Op::Loop && fold_bodies_) n.loop = fold_body(n);
    if (n.op == Op::Switch && fold_bodies_) n.cases = fold_cases(n);
    auto [v, facts] = bounds(n, in_id);
    narrow_by_assumption(in_id, n.type, v, facts);
    if (is_float_valued(n.type) && n.op != Op::Constant)
        if (auto r = fold_to_constant(n, in_id, v, facts)) return *r;
    if (auto r = identity(n, in_id, facts)) return *r;
    return emit(std::move(n), std::move(v), facts);
}

} // namespace watergen::fold
