// Every feature node with the inputs it takes, so a node can be run on its own: by the
// numeric harness (watergen probe), the stress tests and the benches.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "watergen/ir/dsl.h"

namespace watergen {

struct NodeInput {
    std::string name;
    Type type = Type::Float;
};

struct CatalogNode {
    std::string name; // "<axis>.<choice>", e.g. "fresnel.exact"
    std::string description;
    std::vector<NodeInput> inputs;
    std::function<Expr(Graph&, const std::vector<Expr>&)> build;
};

const std::vector<CatalogNode>& node_catalog();

// Each axis file (core/nodes/<axis>.cpp) adds the nodes of its axis.
void append_waves_nodes(std::vector<CatalogNode>& list);
void append_normals_nodes(std::vector<CatalogNode>& list);
void append_refraction_nodes(std::vector<CatalogNode>& list);
void append_extinction_nodes(std::vector<CatalogNode>& list);
void append_reflection_nodes(std::vector<CatalogNode>& list);
void append_fresnel_nodes(std::vector<CatalogNode>& list);
void append_specular_nodes(std::vector<CatalogNode>& list);
void append_foam_nodes(std::vector<CatalogNode>& list);
void append_shore_nodes(std::vector<CatalogNode>& list);
const CatalogNode* find_catalog_node(const std::string& name);
std::string catalog_names(); // "a, b, c"

// A graph whose varyings are the node's inputs (in order) and whose output "value" is the node.
Graph probe_graph(const CatalogNode& node);

} // namespace watergen
