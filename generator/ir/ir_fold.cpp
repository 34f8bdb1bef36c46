#include "watergen/ir/ir_fold.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "watergen/ir/cpu_evaluator.h"

namespace watergen {

size_t FoldFacts::add_fact(std::string text, std::string where) {
    facts.push_back({std::move(text), std::move(where)});
    return std::min(facts.size() - 1, kMaxFacts - 1);
}

std::string describe_facts(const FoldFacts& facts, const FactSet& set) {
    std::string s;
    for (size_t i = 0; i < facts.facts.size() && i < kMaxFacts; ++i) {
        if (!set.test(i)) continue;
        const Fact& f = facts.facts[i];
        s += (s.empty() ? "" : "; ") + f.text + (f.where.empty() ? "" : " [" + f.where + "]");
    }
    return s.empty() ? "no scene fact (constant arithmetic)" : s;
}

namespace {

bool is_float_valued(Type t) { return is_float_numeric(t) || t == Type::Mat3; }

bool pure(Op op) {
    switch (op) {
    case Op::Constant: case Op::Uniform: case Op::Varying: case Op::Texture: case Op::Sample:
    case Op::SampleLevel: case Op::Ddx: case Op::Ddy: return false;
    default: return true;
    }
}

// How a node reads in explain output: its name when it has one, else its operation.
std::string label(const Node& n) {
    if (!n.name.empty() && n.op != Op::Constant) return n.name;
    if (is_infix(n.op)) return std::string("(... ") + op_name(n.op) + " ...)";
    return std::string(op_name(n.op)) + "(...)";
}

std::string spell_values(const std::vector<double>& v) {
    if (v.size() == 1) return fmt::format("{:g}", v[0]);
    std::string s = "(";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt::format("{:g}", v[i]);
    return s + ")";
}

// Evaluates one operation on constant arguments with the CPU evaluator, so folding and the
// reference evaluation agree by construction.
std::optional<std::vector<double>> evaluate_constant(const Node& n, const std::vector<const Node*>& args) {
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

class Folder {
public:
    Folder(const Graph& in, const FoldFacts& facts) : in_(in), f_(facts), map_(in.size(), UINT32_MAX) {
        resolve_quantities();
    }

    void rewrite_all() {
        declare_inputs();
        live_ = in_.live_nodes();
        event_of_.assign(in_.size(), -1);
        for (uint32_t id : live_) map_[id] = rewrite(id);
        for (const auto& o : in_.outputs()) out_.set_output(o.name, map_[o.node]);
        for (const auto& b : in_.bindings())
            if (map_[b.node] != UINT32_MAX) out_.bind(b.quantity, map_[b.node]);
        report_.live_before = live_.size();
    }

    std::vector<FoldEvent>& events() { return report_.events; }

    FoldResult finish() {
        attribute(live_);
        return FoldResult{compact(out_), std::move(report_)};
    }

    // Only the live nodes, renumbered in order: variants that fold to the same computation
    // get the same graph (and the same emitted text, whose temporaries are named by id).
    static Graph compact(const Graph& g) {
        Graph out;
        for (const Parameter& p : g.parameters()) out.declare_parameter(p);
        for (const auto& t : g.textures()) out.declare_texture(t);
        std::vector<uint32_t> map(g.size(), UINT32_MAX);
        for (uint32_t id : g.live_nodes()) {
            Node n = g.node(id);
            for (auto& a : n.args) a = map[a];
            map[id] = out.add(std::move(n));
        }
        for (const auto& o : g.outputs()) out.set_output(o.name, map[o.node]);
        for (const auto& b : g.bindings())
            if (map[b.node] != UINT32_MAX) out.bind(b.quantity, map[b.node]);
        return out;
    }

private:
    // Facts about bound quantities become facts about the parameters or nodes bound to them,
    // so they apply whatever those are called; the report says where each one went.
    void resolve_quantities() {
        std::vector<char> live(in_.size(), 0);
        for (uint32_t id : in_.live_nodes()) live[id] = 1;
        auto resolve = [&](const Quantity& q, const FoldFacts::Bounds& bounds, const FoldFacts::Fixed* fixed) {
            QuantityReach reach = QuantityReach::Unbound;
            for (const auto& b : in_.bindings()) {
                if (!(b.quantity == q)) continue;
                const Node& n = in_.node(b.node);
                reach = live[b.node] ? QuantityReach::Read : std::min(reach, QuantityReach::Unread);
                if (n.op == Op::Uniform && fixed) f_.fixed[n.name] = *fixed;
                else if (n.op == Op::Uniform) f_.parameter_ranges[n.name] = bounds;
                else node_ranges_[b.node] = bounds;
            }
            report_.quantities.push_back({q, reach});
        };
        for (const auto& [q, fixed] : f_.fixed_quantities) {
            FoldFacts::Bounds point{{}, fixed.fact};
            for (double x : fixed.value) point.bounds.push_back(make_interval(x, x));
            resolve(q, point, &fixed);
        }
        for (const auto& [q, bounds] : f_.quantity_ranges) resolve(q, bounds, nullptr);
    }

    void declare_inputs() {
        for (Parameter p : in_.parameters()) {
            if (f_.fixed.count(p.name)) continue;
            if (auto it = f_.parameter_ranges.find(p.name); it != f_.parameter_ranges.end() && it->second.bounds.size() == 1) {
                p.min = it->second.bounds[0].lo;
                p.max = it->second.bounds[0].hi;
            }
            out_.declare_parameter(p);
        }
        for (const auto& t : in_.textures()) out_.declare_texture(t);
    }

    // Adds `n` to the output graph with its bounds and the facts behind them.
    uint32_t emit(Node n, Intervals v, FactSet facts) {
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
                overlap = overlap && std::max(values_[id][c].lo, v[c].lo) <= std::min(values_[id][c].hi, v[c].hi);
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

    uint32_t constant(const Node& like, std::vector<double> values, FactSet facts) {
        Node c;
        c.op = Op::Constant;
        c.type = like.type;
        c.values = std::move(values);
        c.origin = like.origin;
        c.relaxed = like.relaxed;
        Intervals v;
        for (double x : c.values) v.push_back(make_interval(x, x));
        return emit(std::move(c), std::move(v), facts);
    }

    void event(uint32_t in_id, std::string what, FactSet facts) {
        event_of_[in_id] = static_cast<int>(report_.events.size());
        report_.events.push_back({in_id, in_.node(in_id).origin, std::move(what), facts});
    }

    Intervals bounds_of(const FoldFacts::Bounds& b, Type t) const {
        const size_t comps = static_cast<size_t>(component_count(t));
        if (b.bounds.size() == comps) return b.bounds;
        return Intervals(comps, b.bounds.empty() ? Interval{} : b.bounds[0]);
    }

    FactSet single(size_t fact) const {
        FactSet s;
        s.set(std::min(fact, kMaxFacts - 1));
        return s;
    }

    // Bounds and facts of a leaf read.
    std::pair<Intervals, FactSet> leaf_bounds(const Node& n, uint32_t in_id) const {
        if (n.op == Op::Uniform) {
            if (auto it = f_.parameter_ranges.find(n.name); it != f_.parameter_ranges.end())
                return {bounds_of(it->second, n.type), single(it->second.fact)};
            if (const Parameter* p = in_.find_parameter(n.name))
                return {Intervals(static_cast<size_t>(component_count(n.type)), make_interval(p->min, p->max)), {}};
            return {unknown_intervals(n.type, false), {}};
        }
        // Varyings and samples: the scene's input contract; unknown inputs are assumed finite.
        std::string name = n.name;
        if (n.op == Op::Sample || n.op == Op::SampleLevel) name = in_.node(in_.node(in_id).args[0]).name;
        if (auto it = f_.input_ranges.find(name); it != f_.input_ranges.end())
            return {bounds_of(it->second, n.type), single(it->second.fact)};
        return {unknown_intervals(n.type, true), {}};
    }

    bool is_constant(uint32_t id, double x) const {
        const Node& n = out_.node(id);
        if (n.op != Op::Constant || n.values.empty()) return false;
        for (double v : n.values)
            if (v != x) return false;
        return true;
    }

    bool all_finite(uint32_t id) const {
        for (const auto& v : values_[id])
            if (!v.finite) return false;
        return true;
    }

    // `id` standing in for a node of type `t`: scalars widen by a splat.
    std::optional<uint32_t> as_type(uint32_t id, const Node& like) {
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
    bool all_ge(const Intervals& a, const Intervals& b) const {
        const size_t n = std::max(a.size(), b.size());
        for (size_t c = 0; c < n; ++c) {
            const Interval& x = a.size() == 1 ? a[0] : a[c];
            const Interval& y = b.size() == 1 ? b[0] : b[c];
            if (!x.finite || !y.finite || !(x.lo >= y.hi)) return false;
        }
        return true;
    }

    std::optional<uint32_t> identity(const Node& n, uint32_t in_id, const FactSet& all_facts) {
        const auto& a = n.args;
        auto take = [&](uint32_t arg, const std::string& what, FactSet facts) -> std::optional<uint32_t> {
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
                for (const auto& c : values_[a[1]]) v.push_back({-c.hi, -c.lo, c.finite});
                return emit(std::move(neg), std::move(v), facts_[a[0]] | facts_[a[1]]);
            }
            break;
        case Op::Mul:
            if (is_constant(a[1], 1.0)) return take(a[0], "x * 1 -> x", facts_[a[1]]);
            if (is_constant(a[0], 1.0)) return take(a[1], "1 * x -> x", facts_[a[0]]);
            for (int z = 0; z < 2; ++z)
                if (is_constant(a[z], 0.0) && all_finite(a[1 - z])) {
                    event(in_id, label(in_.node(in_id)) + ": x * 0 -> 0 (x is finite)", facts_[a[z]]);
                    return constant(n, std::vector<double>(static_cast<size_t>(component_count(n.type)), 0.0), facts_[a[z]]);
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
            if (decided_false(values_[a[0]])) return take(a[2], "select(false, a, b) -> b", facts_[a[0]]);
            if (a[1] == a[2]) return take(a[1], "select(c, a, a) -> a", {});
            break;
        case Op::Max:
            if (all_ge(values_[a[0]], values_[a[1]])) return take(a[0], "max(a, b) -> a (a >= b)", all_facts);
            if (all_ge(values_[a[1]], values_[a[0]])) return take(a[1], "max(a, b) -> b (b >= a)", all_facts);
            break;
        case Op::Min:
            if (all_ge(values_[a[1]], values_[a[0]])) return take(a[0], "min(a, b) -> a (a <= b)", all_facts);
            if (all_ge(values_[a[0]], values_[a[1]])) return take(a[1], "min(a, b) -> b (b <= a)", all_facts);
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
        default: break;
        }
        return std::nullopt;
    }

    uint32_t rewrite(uint32_t in_id) {
        Node n = in_.node(in_id);
        for (auto& a : n.args) a = map_[a];

        if (n.op == Op::Uniform) {
            if (auto it = f_.fixed.find(n.name); it != f_.fixed.end() &&
                it->second.value.size() == static_cast<size_t>(component_count(n.type))) {
                report_.folded_parameters[n.name] = it->second.value;
                event(in_id, n.name + " is fixed to " + spell_values(it->second.value), single(it->second.fact));
                return constant(n, it->second.value, single(it->second.fact));
            }
        }

        Intervals v;
        FactSet facts;
        if (n.op == Op::Uniform || n.op == Op::Varying || n.op == Op::Sample || n.op == Op::SampleLevel) {
            auto [b, fs] = leaf_bounds(n, in_id);
            v = std::move(b);
            facts = fs;
        } else {
            std::vector<const Intervals*> args;
            std::vector<Type> types;
            for (uint32_t a : n.args) {
                args.push_back(&values_[a]);
                types.push_back(out_.node(a).type);
                facts |= facts_[a];
            }
            v = node_intervals(n, args, types);
        }
        if (auto it = node_ranges_.find(in_id); it != node_ranges_.end()) {
            // An assumption the computed bounds contradict cannot hold anywhere; ignore it
            // rather than fold by an empty range.
            const Intervals assumed = bounds_of(it->second, n.type);
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

        if (is_float_valued(n.type) && n.op != Op::Constant) {
            // Constant arguments only: evaluate.
            bool constant_args = pure(n.op) && !n.args.empty();
            std::vector<const Node*> arg_nodes;
            for (uint32_t a : n.args) {
                constant_args = constant_args && out_.node(a).op == Op::Constant;
                arg_nodes.push_back(&out_.node(a));
            }
            if (constant_args)
                if (auto value = evaluate_constant(n, arg_nodes)) {
                    if (facts.any()) event(in_id, label(in_.node(in_id)) + " of constants -> " + spell_values(*value), facts);
                    return constant(n, std::move(*value), facts);
                }
            // Bounds that pin the value down.
            bool point = !v.empty(), vanishing = !v.empty(), zero = true;
            for (const auto& c : v) {
                point = point && c.is_point();
                vanishing = vanishing && c.finite && std::fabs(c.lo) <= f_.vanish && std::fabs(c.hi) <= f_.vanish;
                zero = zero && c.lo == 0.0 && c.hi == 0.0;
            }
            if (point) {
                std::vector<double> values;
                for (const auto& c : v) values.push_back(c.lo);
                event(in_id, label(in_.node(in_id)) + " is always " + spell_values(values), facts);
                return constant(n, std::move(values), facts);
            }
            if (vanishing && !zero) {
                double bound = 0.0;
                for (const auto& c : v) bound = std::max({bound, std::fabs(c.lo), std::fabs(c.hi)});
                event(in_id, label(in_.node(in_id)) + fmt::format(" vanishes (|value| <= {:.2g}) -> 0", bound), facts);
                return constant(n, std::vector<double>(v.size(), 0.0), facts);
            }
        }
        if (auto r = identity(n, in_id, facts)) return *r;
        return emit(std::move(n), std::move(v), facts);
    }

    // Which rewrite made each removed node unnecessary: the outermost one on its path to the
    // output (consumers have larger ids, so a descending walk meets them first).
    void attribute(const std::vector<uint32_t>& live) {
        const std::vector<uint32_t> live_out = out_.live_nodes();
        std::vector<char> out_live(out_.size(), 0);
        for (uint32_t id : live_out) out_live[id] = 1;
        report_.live_after = live_out.size();
        std::vector<char> removed(in_.size(), 0);
        for (uint32_t id : live) removed[id] = !out_live[map_[id]];
        // A term folded into a constant is removed by its own rewrite; other removed nodes by
        // the outermost rewrite that stopped reading them.
        for (uint32_t id : live)
            if (in_.node(id).op != Op::Constant && out_.node(map_[id]).op == Op::Constant) removed[id] = 1;
        std::vector<int> cause(in_.size(), -1);
        for (auto it = live.rbegin(); it != live.rend(); ++it) {
            const uint32_t y = *it;
            const bool own_constant = event_of_[y] >= 0 && out_.node(map_[y]).op == Op::Constant;
            if (own_constant) cause[y] = event_of_[y];
            const int cy = removed[y] && cause[y] >= 0 ? cause[y] : event_of_[y] >= 0 ? event_of_[y] : cause[y];
            for (uint32_t a : in_.node(y).args)
                if (removed[a] && cause[a] < 0 && cy >= 0) cause[a] = cy;
        }
        for (uint32_t id : live) {
            if (!removed[id]) continue;
            const Node& n = in_.node(id);
            const bool leaf = n.op == Op::Constant || n.op == Op::Uniform || n.op == Op::Varying || n.op == Op::Texture;
            report_.removed.push_back({id, n.origin, label(n), !leaf && !n.name.empty(), cause[id] >= 0 ? cause[id] : event_of_[id]});
        }
        // Inputs no longer read, with the facts of the rewrite that cut them.
        std::map<std::string, FactSet> params, textures;
        std::map<std::string, bool> still_param, still_texture;
        for (uint32_t id : live_out) {
            const Node& n = out_.node(id);
            if (n.op == Op::Uniform) still_param[n.name] = true;
            if (n.op == Op::Texture) still_texture[n.name] = true;
        }
        for (uint32_t id : live) {
            const Node& n = in_.node(id);
            if (n.op != Op::Uniform && n.op != Op::Texture) continue;
            auto& still = n.op == Op::Uniform ? still_param : still_texture;
            if (still.count(n.name)) continue;
            const int e = event_of_[id] >= 0 ? event_of_[id] : cause[id];
            FactSet fs = e >= 0 ? report_.events[static_cast<size_t>(e)].facts : FactSet{};
            (n.op == Op::Uniform ? params : textures)[n.name] |= fs;
        }
        for (const auto& [name, fs] : params) report_.removed_parameters.push_back({name, fs});
        for (const auto& [name, fs] : textures) report_.removed_textures.push_back({name, fs});
    }

    const Graph& in_;
    FoldFacts f_; // with the bound quantities resolved
    std::map<uint32_t, FoldFacts::Bounds> node_ranges_; // computed nodes bound to a quantity
    Graph out_;
    std::vector<uint32_t> map_;
    std::vector<Intervals> values_;
    std::vector<FactSet> facts_;
    std::vector<int> event_of_;
    std::vector<uint32_t> live_;
    FoldReport report_;
};

// The facts minus those in `drop`: what the analysis would know without them.
FoldFacts without(const FoldFacts& f, const FactSet& drop) {
    FoldFacts out = f;
    out.refine_causes = false;
    auto prune = [&](auto& map) {
        for (auto it = map.begin(); it != map.end();)
            it = drop.test(std::min(it->second.fact, kMaxFacts - 1)) ? map.erase(it) : std::next(it);
    };
    prune(out.fixed);
    prune(out.parameter_ranges);
    prune(out.input_ranges);
    prune(out.fixed_quantities);
    prune(out.quantity_ranges);
    return out;
}

std::set<std::string> event_keys(const Graph& g, const FoldFacts& f) {
    Folder folder(g, f);
    folder.rewrite_all();
    std::set<std::string> keys;
    for (const auto& e : folder.events()) keys.insert(std::to_string(e.node) + "|" + e.what);
    return keys;
}

} // namespace

FoldResult fold_graph(const Graph& g, const FoldFacts& facts) {
    Folder main(g, facts);
    main.rewrite_all();
    if (facts.refine_causes) {
        // Bounds carry every fact that narrowed them, most of which did not matter. A fact
        // caused a rewrite when, without it, the rewrite does not happen.
        std::vector<FoldEvent>& events = main.events();
        FactSet used;
        for (const auto& e : events) used |= e.facts;
        if (used.any()) {
            const std::set<std::string> bare = event_keys(g, without(facts, used));
            std::vector<FactSet> necessary(events.size());
            for (size_t k = 0; k < kMaxFacts; ++k) {
                if (!used.test(k)) continue;
                const std::set<std::string> keys = event_keys(g, without(facts, FactSet().set(k)));
                for (size_t i = 0; i < events.size(); ++i)
                    if (events[i].facts.test(k) && !keys.count(std::to_string(events[i].node) + "|" + events[i].what))
                        necessary[i].set(k);
            }
            for (size_t i = 0; i < events.size(); ++i) {
                if (bare.count(std::to_string(events[i].node) + "|" + events[i].what)) events[i].facts.reset();
                else if (necessary[i].any()) events[i].facts = necessary[i];
                // else: several facts suffice each on their own; keep them all.
            }
        }
    }
    return main.finish();
}

} // namespace watergen
