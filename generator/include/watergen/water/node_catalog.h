// Every feature node with the inputs it takes, so a node can be run on its own: by the
// numeric harness (watergen probe), the stress tests and the benches.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "watergen/ir/core/dsl.h"

namespace watergen {

struct NodeInput {
    std::string name;
    Type type = Type::Float;
};

struct CatalogNode {
    std::string name; // "<axis>.<choice>", e.g. "fresnel.exact"
    std::string description{};
    std::vector<NodeInput> inputs{};
    std::function<Expr(Graph&, const std::vector<Expr>&)> build{};
    std::string approximates{}; // the catalog node this one approximates, or ""
    Author author{};            // a project's node: where it was registered (axis_registry.h)
};

// Per axis of the registry (axis_registry.h): a node per choice that has one ("fresnel.exact"),
// then the axis' extra nodes ("waves.gerstner.normal").
const std::vector<CatalogNode>& node_catalog();

const CatalogNode* find_catalog_node(const std::string& name);
std::string catalog_names(); // "a, b, c"

// A graph whose varyings are the node's inputs (in order) and whose output "value" is the node;
// a project's node builds as its author, its input names checked as identifiers.
Graph probe_graph(const CatalogNode& node);

} // namespace watergen
