// The fold pass's first step: a switch whose selector the facts decide (a constant, or a
// parameter the scene fixes) becomes the selected case, inlined into the graph, so the rest of
// the pass folds the case's nodes like any others.
#include <map>

#include "folder.h"

namespace watergen::fold {

namespace {

// The selector's value when the facts decide it.
std::optional<double> decided_selector(const Graph& g, const Node& sw, const FoldFacts& facts) {
    const Node& s = g.node(sw.args[0]);
    if (s.op == Op::Constant && s.values.size() == 1) return s.values[0];
    if (s.op != Op::Uniform) return std::nullopt;
    const auto it = facts.fixed.find(s.name);
    if (it == facts.fixed.end() || it->second.value.size() != 1) return std::nullopt;
    return it->second.value[0];
}

// Adds the selected case of `sw` to `out` (its captured values read `map` of the switch's
// arguments); returns the out nodes of its results.
std::vector<uint32_t> inline_case(const Node& sw, size_t c, const std::vector<uint32_t>& map,
                                  Graph& out) {
    const SwitchCases& cases = *sw.cases;
    const Graph& body = *cases.cases[c];
    std::vector<uint32_t> bmap(body.size(), UINT32_MAX);
    for (uint32_t id : body.live_nodes()) {
        Node n = body.node(id);
        if (n.op == Op::Captured) {
            bmap[id] = map[sw.args[cases.case_args[c] + static_cast<size_t>(n.values[0])]];
            continue;
        }
        for (auto& a : n.args)
            a = bmap[a];
        bmap[id] = out.add(std::move(n));
    }
    for (const auto& b : body.bindings())
        if (bmap[b.node] != UINT32_MAX) out.bind(b.quantity, bmap[b.node]);
    std::vector<uint32_t> results;
    for (const auto& o : body.outputs())
        results.push_back(bmap[o.node]);
    return results;
}

} // namespace

std::shared_ptr<const SwitchCases> Folder::fold_cases(const Node& n) const {
    const SwitchCases& cases = *n.cases;
    auto folded = std::make_shared<SwitchCases>(cases);
    bool any = false;
    for (size_t c = 0; c < cases.cases.size(); ++c) {
        const Graph& body = *cases.cases[c];
        std::map<uint32_t, Intervals> leaves;
        for (uint32_t id : body.live_nodes()) {
            const Node& b = body.node(id);
            if (b.op != Op::Captured || b.values.empty()) continue;
            const size_t arg = cases.case_args[c] + static_cast<size_t>(b.values[0]);
            if (arg < n.args.size()) leaves[id] = values_[n.args[arg]];
        }
        std::optional<Graph> case_graph =
            fold_inner(body, std::move(leaves), "the switch's arguments");
        if (!case_graph) continue;
        folded->cases[c] = std::make_shared<const Graph>(std::move(*case_graph));
        any = true;
    }
    return any ? folded : n.cases;
}

std::optional<Graph> inline_decided_switches(const Graph& g, const FoldFacts& facts) {
    bool any = false;
    for (uint32_t id = 0; id < g.size(); ++id)
        any = any || (g.node(id).op == Op::Switch && decided_selector(g, g.node(id), facts));
    if (!any) return std::nullopt;
    Graph out;
    for (const Parameter& p : g.parameters())
        out.declare_parameter(p);
    for (const auto& t : g.textures())
        out.declare_texture(t);
    std::vector<uint32_t> map(g.size(), UINT32_MAX);
    std::map<uint32_t, std::vector<uint32_t>> inlined; // switch -> its results in `out`
    for (uint32_t id = 0; id < g.size(); ++id) {
        Node n = g.node(id);
        if (n.op == Op::Switch) {
            if (auto value = decided_selector(g, n, facts)) {
                inlined[id] = inline_case(n, n.cases->case_for(*value), map, out);
                continue;
            }
        }
        if (n.op == Op::SwitchResult && inlined.count(n.args[0])) {
            map[id] = inlined[n.args[0]][static_cast<size_t>(n.values[0])];
            continue;
        }
        for (auto& a : n.args)
            a = map[a];
        map[id] = out.add(std::move(n));
    }
    Folder::copy_outputs(g, map, out);
    return out;
}

} // namespace watergen::fold
