// Runs a compiled program (block_program.h) over blocks of lanes: one evaluator per thread,
// its arena holding the values alive at once. Private to ir/.
#pragma once

#include <vector>

#include "block_program.h"

namespace watergen {

class BlockEvaluator {
  public:
    // Computes the program's prologue (its lane-invariant values) once.
    BlockEvaluator(const Program& program, const EvalInputs& in);

    // Evaluates lanes [begin, begin + count) (block_error() must have passed them).
    void run(size_t begin, size_t count);
    // The root's values for the block's lanes, lane-major, `root_comps` per lane.
    void read_root(size_t count, double* to) const;

  private:
    const Program& program_;
    std::vector<double> wide_;
    std::vector<float> narrow_;
    Exec exec_;
};

// The kernel of a loop instruction: every lane iterates until the trip count or until its exit
// condition is false; the body runs over all lanes, and a lane that has left keeps its carried
// values (the GPU's per-pixel break).
Kernel loop_kernel(bool wide);

} // namespace watergen
