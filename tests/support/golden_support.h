// Evaluates one node function over a list of scalar inputs on the CPU.
#pragma once

#include <functional>
#include <vector>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"

namespace watergen::test {

inline std::vector<double> eval_scalar_node(const std::function<Expr(Graph&, Expr)>& node,
                                            const std::vector<double>& xs,
                                            EvalPrecision precision = EvalPrecision::Double) {
    Graph g;
    Expr x = varying(g, "x", Type::Float);
    RelaxedScope relaxed(g, true); // half mode rounds every operation of the node
    g.set_output("out", node(g, x).id());
    EvalInputs in;
    in.lanes = xs.size();
    in.varyings["x"] = xs;
    const EvalResult r = evaluate(g, "out", in, precision);
    if (!r.ok()) throw std::runtime_error(r.error);
    return r.values;
}

} // namespace watergen::test
