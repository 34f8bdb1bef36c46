// The fold pass: its driver, the report of what it removed and why, and the refinement of each
// rewrite's causes to the facts it needed. The rewrite rules are in ir_fold_rules.cpp.
#include "watergen/ir/fold/ir_fold.h"

#include <algorithm>
#include <optional>
#include <set>

#include "folder.h"

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

namespace fold {

Folder::Folder(const Graph& in, const FoldFacts& facts, bool fold_bodies)
    : in_(in), declarations_(in), fold_bodies_(fold_bodies), f_(facts),
      map_(in.size(), UINT32_MAX) {
    resolve_quantities();
}

Folder::Folder(const Graph& body, const Graph& declarations, const FoldFacts& facts,
               std::map<uint32_t, FoldFacts::Bounds> leaves)
    : in_(body), declarations_(declarations), f_(facts), node_ranges_(std::move(leaves)),
      map_(body.size(), UINT32_MAX) {
    f_.refine_causes = false;
}

void Folder::rewrite_all() {
    declare_inputs();
    live_ = in_.live_nodes();
    event_of_.assign(in_.size(), -1);
    for (uint32_t id : live_)
        map_[id] = rewrite(id);
    for (const auto& o : in_.outputs())
        out_.set_output(o.name, map_[o.node]);
    for (const auto& b : in_.bindings())
        if (map_[b.node] != UINT32_MAX) out_.bind(b.quantity, map_[b.node]);
    report_.live_before = live_.size();
}

FoldResult Folder::finish() {
    attribute(live_);
    return FoldResult{compact(out_), std::move(report_)};
}

Graph Folder::compact(const Graph& g) {
    Graph out;
    for (const Parameter& p : g.parameters())
        out.declare_parameter(p);
    for (const auto& t : g.textures())
        out.declare_texture(t);
    std::vector<uint32_t> map(g.size(), UINT32_MAX);
    for (uint32_t id : g.live_nodes()) {
        Node n = g.node(id);
        for (auto& a : n.args)
            a = map[a];
        map[id] = out.add(std::move(n));
    }
    copy_outputs(g, map, out);
    return out;
}

void Folder::copy_outputs(const Graph& from, const std::vector<uint32_t>& map, Graph& to) {
    for (const auto& o : from.outputs())
        to.set_output(o.name, map[o.node]);
    for (const auto& b : from.bindings())
        if (map[b.node] != UINT32_MAX) to.bind(b.quantity, map[b.node]);
}

// Facts about bound quantities become facts about the parameters or nodes bound to them,
// so they apply whatever those are called; the report says where each one went.
void Folder::resolve_quantities() {
    std::vector<char> live(in_.size(), 0);
    for (uint32_t id : in_.live_nodes())
        live[id] = 1;
    auto resolve = [&](const Quantity& q, const FoldFacts::Bounds& bounds,
                       const FoldFacts::Fixed* fixed) {
        QuantityReach reach = QuantityReach::Unbound;
        for (const auto& b : in_.bindings()) {
            if (!(b.quantity == q)) continue;
            const Node& n = in_.node(b.node);
            reach = live[b.node] ? QuantityReach::Read : std::min(reach, QuantityReach::Unread);
            if (n.op == Op::Uniform && fixed)
                f_.fixed[n.name] = *fixed;
            else if (n.op == Op::Uniform)
                f_.parameter_ranges[n.name] = bounds;
            else
                node_ranges_[b.node] = bounds;
        }
        report_.quantities.push_back({q, reach});
    };
    for (const auto& [q, fixed] : f_.fixed_quantities) {
        FoldFacts::Bounds point{{}, fixed.fact};
        for (double x : fixed.value)
            point.bounds.push_back(make_interval(x, x));
        resolve(q, point, &fixed);
    }
    for (const auto& [q, bounds] : f_.quantity_ranges)
        resolve(q, bounds, nullptr);
}

void Folder::declare_inputs() {
    // What host rules read (runtime/host_values.h): the host computes from them, fixed or not.
    std::set<std::string> host_inputs;
    for (const Parameter& p : in_.parameters())
        if (p.host.rule != HostRule::Given) {
            host_inputs.insert(p.name);
            host_inputs.insert(p.host.inputs.begin(), p.host.inputs.end());
        }
    for (Parameter p : in_.parameters()) {
        if (auto it = f_.fixed.find(p.name); it != f_.fixed.end()) {
            // Loop bodies read arrays element by element, which the fold does not turn into
            // constants: a fixed array stays a parameter whose default is the fixed value. So
            // does a value a host rule reads or makes.
            if (!p.array_size && !host_inputs.count(p.name)) continue;
            // The host computes from the fixed value: the parameter is folded all the same
            // (a writer refuses another value, a companion pass takes this one).
            if (host_inputs.count(p.name) && !p.array_size)
                report_.folded_parameters[p.name] = it->second.value;
            if (it->second.value.size() == p.default_value.size())
                p.default_value = it->second.value;
        }
        if (auto it = f_.parameter_ranges.find(p.name);
            it != f_.parameter_ranges.end() && it->second.bounds.size() == 1) {
            p.min = it->second.bounds[0].lo;
            p.max = it->second.bounds[0].hi;
        }
        out_.declare_parameter(p);
    }
    for (const auto& t : in_.textures())
        out_.declare_texture(t);
}

// Which rewrite made each removed node unnecessary: the outermost one on its path to the
// output (consumers have larger ids, so a descending walk meets them first).
void Folder::attribute(const std::vector<uint32_t>& live) {
    const std::vector<uint32_t> live_out = out_.live_nodes();
    std::vector<char> out_live(out_.size(), 0);
    for (uint32_t id : live_out)
        out_live[id] = 1;
    report_.live_after = live_out.size();
    std::vector<char> removed(in_.size(), 0);
    for (uint32_t id : live)
        removed[id] = !out_live[map_[id]];
    // A term folded into a constant is removed by its own rewrite; other removed nodes by
    // the outermost rewrite that stopped reading them.
    for (uint32_t id : live)
        if (in_.node(id).op != Op::Constant && out_.node(map_[id]).op == Op::Constant)
            removed[id] = 1;
    std::vector<int> cause(in_.size(), -1);
    for (auto it = live.rbegin(); it != live.rend(); ++it) {
        const uint32_t y = *it;
        const bool own_constant = event_of_[y] >= 0 && out_.node(map_[y]).op == Op::Constant;
        if (own_constant) cause[y] = event_of_[y];
        const int cy = removed[y] && cause[y] >= 0 ? cause[y]
                       : event_of_[y] >= 0         ? event_of_[y]
                                                   : cause[y];
        for (uint32_t a : in_.node(y).args)
            if (removed[a] && cause[a] < 0 && cy >= 0) cause[a] = cy;
    }
    for (uint32_t id : live) {
        if (!removed[id]) continue;
        const Node& n = in_.node(id);
        const bool leaf = n.op == Op::Constant || n.op == Op::Uniform || n.op == Op::Varying ||
                          n.op == Op::Texture;
        report_.removed.push_back({id, n.origin, label(n), !leaf && !n.name.empty(),
                                   cause[id] >= 0 ? cause[id] : event_of_[id]});
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
    for (const auto& [name, fs] : params)
        report_.removed_parameters.push_back({name, fs});
    for (const auto& [name, fs] : textures)
        report_.removed_textures.push_back({name, fs});
}

} // namespace fold

namespace {

using fold::Folder;

// The facts minus those in `drop`: what the analysis would know without them.
FoldFacts without(const FoldFacts& f, const FactSet& drop) {
    FoldFacts out = f;
    out.refine_causes = false;
    auto prune = [&](auto& map) {
        for (auto it = map.begin(); it != map.end();)
            it =
                drop.test(std::min(it->second.fact, kMaxFacts - 1)) ? map.erase(it) : std::next(it);
    };
    prune(out.fixed);
    prune(out.parameter_ranges);
    prune(out.input_ranges);
    prune(out.fixed_quantities);
    prune(out.quantity_ranges);
    return out;
}

std::set<std::string> event_keys(const Graph& g, const FoldFacts& f) {
    Folder folder(g, f, false);
    folder.rewrite_all();
    std::set<std::string> keys;
    for (const auto& e : folder.events())
        keys.insert(std::to_string(e.node) + "|" + e.what);
    return keys;
}

} // namespace

FoldResult fold_graph(const Graph& graph, const FoldFacts& facts) {
    const std::optional<Graph> inlined = fold::inline_decided_switches(graph, facts);
    const Graph& g = inlined ? *inlined : graph;
    Folder main(g, facts);
    main.rewrite_all();
    if (facts.refine_causes) {
        // Bounds carry every fact that narrowed them, most of which did not matter. A fact
        // caused a rewrite when, without it, the rewrite does not happen.
        std::vector<FoldEvent>& events = main.events();
        FactSet used;
        for (const auto& e : events)
            used |= e.facts;
        if (used.any()) {
            const std::set<std::string> bare = event_keys(g, without(facts, used));
            std::vector<FactSet> necessary(events.size());
            for (size_t k = 0; k < kMaxFacts; ++k) {
                if (!used.test(k)) continue;
                const std::set<std::string> keys = event_keys(g, without(facts, FactSet().set(k)));
                for (size_t i = 0; i < events.size(); ++i)
                    if (events[i].facts.test(k) &&
                        !keys.count(std::to_string(events[i].node) + "|" + events[i].what))
                        necessary[i].set(k);
            }
            for (size_t i = 0; i < events.size(); ++i) {
                if (bare.count(std::to_string(events[i].node) + "|" + events[i].what))
                    events[i].facts.reset();
                else if (necessary[i].any())
                    events[i].facts = necessary[i];
                // else: several facts suffice each on their own; keep them all.
            }
        }
    }
    return main.finish();
}

} // namespace watergen
