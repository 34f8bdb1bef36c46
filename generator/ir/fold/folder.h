// The fold pass over one graph (ir_fold.h), shared by its two halves: the pass driver, report
// and cause refinement (ir_fold.cpp) and the rewrite rules (ir_fold_rules.cpp). Private to ir/.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "watergen/ir/fold/ir_fold.h"

namespace watergen::fold {

// How a node reads in explain output: its name when it has one, else its operation.
std::string label(const Node& n);

// `g` with every switch whose selector the facts decide replaced by its selected case
// (ir_fold_switch.cpp); nullopt when there is none.
std::optional<Graph> inline_decided_switches(const Graph& g, const FoldFacts& facts);

class Folder {
  public:
    // `fold_bodies`: also fold inside loop bodies (fold_body()); the cause refinement's reruns,
    // which only compare the graph's own rewrites, leave them alone.
    Folder(const Graph& in, const FoldFacts& facts, bool fold_bodies = true);
    // A loop body's folder: `leaves` bounds its LoopIndex, Carried and Captured nodes (by id);
    // `declarations` is the graph that declares the body's parameters (the outermost one).
    Folder(const Graph& body, const Graph& declarations, const FoldFacts& facts,
           std::map<uint32_t, FoldFacts::Bounds> leaves);

    void rewrite_all();
    std::vector<FoldEvent>& events() { return report_.events; }
    FoldResult finish();

    // Only the live nodes, renumbered in order: variants that fold to the same computation
    // get the same graph (and the same emitted text, whose temporaries are named by id).
    static Graph compact(const Graph& g);
    // Sets `to`'s outputs and quantity bindings from `from`'s, through the node map.
    static void copy_outputs(const Graph& from, const std::vector<uint32_t>& map, Graph& to);

  private:
    // The pass (ir_fold.cpp).
    void resolve_quantities();
    void declare_inputs();
    void attribute(const std::vector<uint32_t>& live);

    // The rewrite rules (ir_fold_rules.cpp).
    uint32_t rewrite(uint32_t in_id);
    std::pair<Intervals, FactSet> bounds(const Node& n, uint32_t in_id) const;
    void narrow_by_assumption(uint32_t in_id, Type t, Intervals& v, FactSet& facts) const;
    std::optional<uint32_t> fold_to_constant(const Node& n, uint32_t in_id, const Intervals& v,
                                             const FactSet& facts);
    std::optional<uint32_t> identity(const Node& n, uint32_t in_id, const FactSet& all_facts);
    uint32_t emit(Node n, Intervals v, FactSet facts);
    uint32_t constant(const Node& like, std::vector<double> values, FactSet facts);
    void event(uint32_t in_id, std::string what, FactSet facts);
    Intervals bounds_of(const FoldFacts::Bounds& b, Type t) const;
    FactSet single(size_t fact) const;
    // A parameter's or input's bounds; `g` is the input graph or a loop body in it.
    std::pair<Intervals, FactSet> leaf_bounds(const Graph& g, const Node& n, uint32_t id) const;

    // Loops, analysed by iterating their bodies (loop_bounds.cpp).
    using State = std::vector<Intervals>;
    std::pair<Intervals, FactSet> loop_bounds(const Node& n,
                                              const std::vector<const Intervals*>& args) const;
    struct BodyScratch {
        std::vector<uint32_t> live;            // the body's live nodes
        std::vector<uint32_t> next;            // the node of each carried value's next value
        mutable std::vector<Intervals> values; // per body node, reused round after round
    };
    std::pair<State, FactSet> body_step(const LoopBody& loop, const BodyScratch& scratch,
                                        const State& carried,
                                        const std::vector<const Intervals*>& captured) const;
    static Intervals loop_result_bounds(const Node& result, const Node& loop_node,
                                        const Intervals& loop_bounds);
    // The union of the states after 0, 1, ... iterations from `state`: U = U u f(U) until
    // nothing moves (`settled`) or every iteration is accounted for; a bound still moving after
    // kStepByStep rounds is widened to a threshold. nullopt when it does not settle.
    std::optional<State> union_of_states(const LoopBody& loop, const BodyScratch& scratch,
                                         State state, const std::vector<const Intervals*>& captured,
                                         FactSet& facts, bool& settled) const;
    // Bounds of the carried values at the start of every iteration (the union of the states
    // before each); nullopt when the analysis gives up.
    std::optional<State> carried_hull(const LoopBody& loop, const BodyScratch& scratch,
                                      const State& initial,
                                      const std::vector<const Intervals*>& captured,
                                      FactSet& facts) const;
    // The loop's body folded by what holds in every iteration (its index, the carried values'
    // hull, the captured values' bounds, the scene's facts); the same body when nothing folds.
    std::shared_ptr<const LoopBody> fold_body(const Node& n) const;
    static BodyScratch scratch_for(const LoopBody& loop);
    // A switch's cases folded by their captured values' bounds and the scene's facts
    // (ir_fold_switch.cpp); the same cases when nothing folds.
    std::shared_ptr<const SwitchCases> fold_cases(const Node& n) const;
    // A loop body or switch case folded with its leaves (by id) within `leaves`, which
    // `bounded_by` names; nullopt when nothing folds.
    std::optional<Graph> fold_inner(const Graph& inner, std::map<uint32_t, Intervals> leaves,
                                    const char* bounded_by) const;
    bool is_constant(uint32_t id, double x) const;
    bool all_finite(uint32_t id) const;
    std::optional<uint32_t> as_type(uint32_t id, const Node& like);
    bool all_ge(const Intervals& a, const Intervals& b) const;

    const Graph& in_;
    const Graph& declarations_; // where the parameters read in in_ are declared
    bool fold_bodies_ = true;
    FoldFacts f_;                                       // with the bound quantities resolved
    std::map<uint32_t, FoldFacts::Bounds> node_ranges_; // computed nodes bound to a quantity
    Graph out_;
    std::vector<uint32_t> map_;
    std::vector<Intervals> values_;
    std::vector<FactSet> facts_;
    std::vector<int> event_of_;
    std::vector<uint32_t> live_;
    FoldReport report_;
};

} // namespace watergen::fold
