// CPU evaluation of catalog nodes over input tuples laid out like the probe harness
// (tuple-major, the node's inputs in order), and the synthetic scene camera as a helper.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/water/node_catalog.h"

namespace watergen::test {

using Uniforms = std::map<std::string, std::vector<double>>;

struct NodeValues {
    std::vector<double> values; // tuples x components
    int components = 0;
    double at(size_t tuple, int c = 0) const {
        return values[tuple * static_cast<size_t>(components) + static_cast<size_t>(c)];
    }
};

// The catalog node's graph exactly as the probe builds it (relaxed, so half mode rounds every
// operation of the node), evaluated on the CPU.
inline NodeValues eval_catalog(const std::string& name, const std::vector<double>& tuples,
                               EvalPrecision precision = EvalPrecision::Double,
                               const Uniforms& uniforms = {},
                               const std::map<std::string, TextureView>& textures = {}) {
    const CatalogNode* node = find_catalog_node(name);
    if (!node) throw std::runtime_error("no catalog node " + name);
    const Graph g = probe_graph(*node);
    size_t stride = 0;
    for (const auto& in : node->inputs)
        stride += static_cast<size_t>(component_count(in.type));
    EvalInputs eval;
    eval.uniforms = uniforms;
    eval.textures = textures;
    eval.lanes = tuples.size() / stride;
    size_t offset = 0;
    for (const auto& in : node->inputs) {
        const int n = component_count(in.type);
        auto& v = eval.varyings[in.name];
        for (size_t t = 0; t < eval.lanes; ++t)
            for (int c = 0; c < n; ++c)
                v.push_back(tuples[t * stride + offset + static_cast<size_t>(c)]);
        offset += static_cast<size_t>(n);
    }
    const EvalResult r = evaluate(g, "value", eval, precision);
    if (!r.ok()) throw std::runtime_error(name + ": " + r.error);
    return {r.values, r.components};
}

} // namespace watergen::test
