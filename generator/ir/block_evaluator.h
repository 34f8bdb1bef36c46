// The CPU evaluator's engine (cpu_evaluator.cpp drives it): the live nodes of a graph over a
// block of lanes, node after node. Private to ir/.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "watergen/ir/cpu_evaluator.h"

namespace watergen {

constexpr size_t kBlock = 256; // lanes per block: a multiple of 4 (whole quads)

// Where a loop body's leaves read: the iteration, the carried values (the Loop node's storage:
// lane-major, every carried value's components in turn) and the captured outer values. A
// switch case reads captured values only.
struct LoopFrame {
    double index = 0;
    const double* carried = nullptr;
    size_t carried_lane_stride = 0; // 0: one lane for all
    std::vector<size_t> carried_offset;
    struct Source {
        const double* values = nullptr;
        size_t lane_stride = 0, component_stride = 0;
    };
    std::vector<Source> captured;
};

// A node whose arguments are all the same on every lane (constants, parameters and what is
// computed from them alone) is computed once, for one lane, and read by every lane after that:
// a lane-invariant node. A value's storage goes back to a pool after its last user.
class BlockEvaluator {
  public:
    // `params`: the graph whose parameters the Uniform leaves read (a loop body reads its
    // enclosing graph's). `keep`: nodes whose values outlive the run (the outputs read).
    BlockEvaluator(const Graph& g, const Graph& params, const std::vector<uint32_t>& live,
                   const EvalInputs& in, EvalPrecision p, const std::vector<uint32_t>& keep,
                   const LoopFrame* frame = nullptr);
    ~BlockEvaluator();

    // Evaluates lanes [begin, begin + count); returns false and sets error on bad input.
    bool run(size_t begin, size_t count, std::string& error);

    // The values of node id, lane-major; a lane-invariant node holds one lane.
    const double* values(uint32_t id) const { return values_[id].data(); }
    bool invariant(uint32_t id) const { return invariant_[id]; }

  private:
    double arg(const Node&, size_t i, size_t l, int c) const {
        return sources_[i][l * lane_stride_[i] + static_cast<size_t>(c) * component_stride_[i]];
    }
    template <class F> void map2(std::vector<double>& out, int comps, F f) const;
    void bind_arguments(const Node& n);
    bool texture_result(uint32_t id) const;
    bool compute(uint32_t id, const Node& n, int comps, size_t begin, std::vector<double>& out,
                 std::string& error);
    bool compute_leaf(const Node& n, int comps, size_t begin, std::vector<double>& out,
                      std::string& error);
    bool run_loop(uint32_t id, const Node& n, size_t begin, std::vector<double>& out,
                  std::string& error);
    bool run_switch(uint32_t id, const Node& n, size_t begin, std::vector<double>& out,
                    std::string& error);

    const Graph& g_;
    const Graph& params_;
    const std::vector<uint32_t>& live_;
    const EvalInputs& in_;
    EvalPrecision p_;
    const LoopFrame* frame_;
    std::vector<std::vector<double>> values_;
    std::vector<char> invariant_, done_;    // per node: lane-invariant; computed already
    std::vector<size_t> last_use_;          // per node: position in live_ of its last user
    std::vector<int> comps_;                // per node: values per lane
    std::vector<std::vector<double>> pool_; // storage of values no longer needed
    size_t n_ = 0;                          // lanes of the node being computed
    // Of the node being computed, per argument: its values, and the steps between lanes (0 for
    // a lane-invariant argument) and between components (0 for a scalar).
    std::vector<const double*> sources_;
    std::vector<size_t> lane_stride_, component_stride_;
    std::vector<std::vector<double>> narrowed_;
    // Per Loop node (and per case of a Switch node): its body's live nodes, frame and
    // evaluator, made at its first run.
    struct LoopState;
    std::map<uint32_t, std::unique_ptr<LoopState>> loops_;
    std::map<std::pair<uint32_t, size_t>, std::unique_ptr<LoopState>> cases_;
};

} // namespace watergen
