// CPU evaluation of one node over input tuples, laid out like the probe harness: tuple-major,
// the node's inputs in order, vectors as consecutive components.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/water/node_catalog.h"

namespace watergen::test {

using Uniforms = std::map<std::string, std::vector<double>>;
using NodeBuild = std::function<Expr(Graph&, const std::vector<Expr>&)>;

// Builds `build` over varyings named after `inputs` (relaxed, so half mode rounds every
// operation) and evaluates it. Returns tuples x components values.
inline std::vector<double> eval_node(const std::vector<NodeInput>& inputs, const NodeBuild& build,
                                     const std::vector<double>& tuples,
                                     EvalPrecision precision = EvalPrecision::Double,
                                     const Uniforms& uniforms = {}) {
    Graph g;
    std::vector<Expr> vars;
    size_t stride = 0;
    for (const auto& in : inputs) {
        vars.push_back(varying(g, in.name, in.type));
        stride += static_cast<size_t>(component_count(in.type));
    }
    RelaxedScope relaxed(g, true);
    g.set_output("out", build(g, vars).id());
    if (!g.diagnostics().empty())
        throw std::runtime_error("node has diagnostics: " + g.diagnostics().front().message);
    EvalInputs eval;
    eval.uniforms = uniforms;
    eval.lanes = tuples.size() / stride;
    size_t offset = 0;
    for (const auto& in : inputs) {
        const int n = component_count(in.type);
        auto& v = eval.varyings[in.name];
        for (size_t t = 0; t < eval.lanes; ++t)
            for (int c = 0; c < n; ++c)
                v.push_back(tuples[t * stride + offset + static_cast<size_t>(c)]);
        offset += static_cast<size_t>(n);
    }
    const EvalResult r = evaluate(g, "out", eval, precision);
    if (!r.ok()) throw std::runtime_error(r.error);
    return r.values;
}

inline std::vector<double> eval_catalog_node(const std::string& name,
                                             const std::vector<double>& tuples,
                                             EvalPrecision precision = EvalPrecision::Double,
                                             const Uniforms& uniforms = {}) {
    const CatalogNode* node = find_catalog_node(name);
    if (!node) throw std::runtime_error("no catalog node " + name);
    return eval_node(node->inputs, node->build, tuples, precision, uniforms);
}

} // namespace watergen::test
