// Interval arithmetic over IR nodes: for each component, bounds that every GPU evaluation of
// the node stays within, and whether it is surely finite (no inf, no NaN). The fold pass
// (ir_fold.h) decides with these bounds which terms a scene makes constant.
//
// Soundness against real GPUs: arithmetic results are widened outwards by a relative margin
// (about 8 ulp of binary32; 2e-3 for relaxed-precision nodes, which may run at 16 bits;
// more for pow and sin/cos, whose Vulkan precision is looser) so that rounding never carries
// a value past a bound the analysis relies on. Zero bounds stay exact: the sign of a product
// or sum of non-negative floats is exact. Results that can exceed the largest float (65504
// for relaxed nodes) are marked not finite.
#pragma once

#include <limits>
#include <vector>

#include "watergen/ir/core/ir.h"

namespace watergen {

struct Interval {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool finite = false; // every value is a finite number

    bool is_point() const { return finite && lo == hi; }
};

using Intervals = std::vector<Interval>; // one per component (Mat3: 9, column-major)

Interval make_interval(double lo, double hi); // finite when both bounds are
Intervals unknown_intervals(Type t, bool finite);
// Bool intervals: [1, 1] true, [0, 0] false, [0, 1] undecided.
bool decided_true(const Intervals& v);
bool decided_false(const Intervals& v);

// Bounds of `n` from the bounds of its arguments (args[i] for n.args[i], types likewise).
// Leaves (Constant) are handled; Uniform, UniformElement, Varying, Sample and Texture are the
// caller's, who knows the parameter ranges and the scene's input ranges, and get
// unknown_intervals here.
Intervals node_intervals(const Node& n, const std::vector<const Intervals*>& args,
                         const std::vector<Type>& arg_types);

// Bounds of result k of the Switch node `sw` from the bounds of its arguments (args[i] for
// sw.args[i]): the union over its cases, or the selected case's alone when the selector is a
// point. Leaves of a case other than captured values and constants are unknown.
Intervals switch_result_intervals(const Node& sw, size_t k,
                                  const std::vector<const Intervals*>& args);

// Largest finite magnitude of the node's precision (binary32, or binary16 when relaxed).
double largest_finite(bool relaxed);

} // namespace watergen
