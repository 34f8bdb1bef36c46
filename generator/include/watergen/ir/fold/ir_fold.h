// The fold pass: specialises a fragment graph to what a scene guarantees. Parameters the
// scene fixes become constants; known ranges (of parameters, of inputs, of bound quantities
// such as the water depth, see Graph::bind) bound every node through interval arithmetic
// (interval.h); then
//   constant subexpressions       are evaluated (by the CPU evaluator, the same semantics),
//   a value the bounds pin down   becomes a constant (saturate(depth * k) = 1 when depth >= 1/k),
//   a value within +-vanish       becomes 0 (the one approximation; exp(-k d) for a deep scene),
//   x * 1, 1 * x, x + 0, x - 0, x / 1, -(-x), pow(x, 1), mix(a, b, 0) = a, mix(a, b, 1) = b,
//   mix(a, a, t) = a, select on a decided condition, select(c, a, a) = a, and min / max /
//   clamp / saturate whose outcome the bounds decide
//                                 are replaced by the surviving operand; 0 - x becomes -x,
//   x * 0 = 0                     only when x is provably finite (inf * 0 and NaN * 0 are NaN),
// and what no output reads any more is gone, because emission walks live nodes only. A switch
// whose selector is a constant or a fixed parameter is first replaced by its selected case. Every
// rewrite is recorded with the facts its decision used, for `watergen explain`. The result is
// compacted (live nodes only, renumbered), so variants that fold alike give the same graph;
// bindings of live nodes move with them.
//
// Soundness: bounds hold on every pixel where the result is shown. A fact about a bound
// quantity may hold only where the graph shows that quantity (a water depth on water pixels,
// whose shader discards every water term elsewhere), so folding by it cannot change the image.
// Bool values are never turned into constants (the languages spell them differently);
// their decided value folds the select / and / or that reads them.
#pragma once

#include <bitset>
#include <map>
#include <string>
#include <vector>

#include "watergen/ir/core/ir.h"
#include "watergen/ir/fold/interval.h"

namespace watergen {

constexpr size_t kMaxFacts = 128;
using FactSet = std::bitset<kMaxFacts>;

struct Fact {
    std::string text;  // "water depth 400..4000 m"
    std::string where; // "examples/scenes/open_ocean.json:6:3 /water_depth", "" when built in
};

struct FoldFacts {
    std::vector<Fact> facts; // ids below index this list (at most kMaxFacts)

    struct Fixed {
        std::vector<double> value;
        size_t fact = 0;
    };
    struct Bounds {
        Intervals bounds; // one per component, or one for all
        size_t fact = 0;
    };
    std::map<std::string, Fixed> fixed;             // parameter -> constant value
    std::map<std::string, Bounds> parameter_ranges; // parameter -> range (else its declared one)
    std::map<std::string, Bounds>
        input_ranges; // varying or texture name -> range of what it yields
    // Facts about bound quantities (Graph::bind), whatever their nodes or parameters are
    // called: a quantity bound to a uniform is fixed or ranged like that parameter (over the
    // ones above); one bound to a computed node narrows that node's bounds.
    std::map<Quantity, Fixed> fixed_quantities;
    std::map<Quantity, Bounds> quantity_ranges;
    double vanish = 1e-7; // |value| <= vanish folds to 0
    // Narrow each rewrite's facts to those without which it would not happen (one extra
    // fold per fact in use): explain names causes, not every fact that touched a bound.
    bool refine_causes = true;

    size_t add_fact(std::string text, std::string where);
};

struct FoldEvent {
    uint32_t node = 0;  // id in the input graph
    std::string origin; // feature node, e.g. "shore.soft"
    std::string what;   // "saturate(...) is always 1", "mix(a, b, 1) -> b"
    FactSet facts;      // facts the decision used; none for plain constant arithmetic
};

struct RemovedTerm {
    uint32_t node = 0; // id in the input graph
    std::string origin;
    std::string name;   // the node's name, or its operation
    bool named = false; // an operation the node author named (a term), not a leaf or a temporary
    int event = -1;     // index into FoldReport::events of the rewrite that cut it, -1 if none
};

struct RemovedInput {
    std::string name; // parameter or texture
    FactSet facts;    // why it is no longer read
};

// Whether a quantity the facts speak of reached the graph.
enum class QuantityReach {
    Read,    // a live node is bound to it: its fact applied
    Unread,  // bound, but this graph does not read it (a variant without that quantity)
    Unbound, // no node is bound to it: the fact could not apply anywhere
};

struct QuantityUse {
    Quantity quantity;
    QuantityReach reach = QuantityReach::Unbound;
};

struct FoldReport {
    std::vector<FoldEvent> events;
    std::vector<QuantityUse> quantities; // every quantity of fixed_quantities and quantity_ranges
    std::vector<RemovedTerm> removed;    // nodes live before, dead after, ascending id
    std::vector<RemovedInput> removed_parameters, removed_textures;
    std::map<std::string, std::vector<double>> folded_parameters; // fixed parameters that were read
    size_t live_before = 0, live_after = 0;
};

struct FoldResult {
    Graph graph;
    FoldReport report;
};

// Folds `g` (which must be free of type errors) under `facts`. Parameters stay declared with
// their ranges narrowed to facts.parameter_ranges (scalar ranges only; per-component ones
// are used by the analysis); fixed parameters are no longer declared, save arrays (loop
// bodies, which the fold leaves alone, read them): a fixed array stays declared with the fixed
// value as its default. Cost: linear in the
// live graph, plus one tiny CPU evaluation per constant subexpression.
FoldResult fold_graph(const Graph& g, const FoldFacts& facts);

// "water depth 400..4000 m [open_ocean.json:6:3 /water_depth]; ..." for the facts in `set`.
std::string describe_facts(const FoldFacts& facts, const FactSet& set);

} // namespace watergen
