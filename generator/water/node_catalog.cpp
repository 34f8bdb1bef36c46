#include "watergen/water/node_catalog.h"


namespace watergen {

const std::vector<CatalogNode>& node_catalog() {
    static const std::vector<CatalogNode> list = [] {
        std::vector<CatalogNode> nodes;
        append_waves_nodes(nodes);
        append_normals_nodes(nodes);
        append_refraction_nodes(nodes);
        append_extinction_nodes(nodes);
        append_reflection_nodes(nodes);
        append_fresnel_nodes(nodes);
        append_specular_nodes(nodes);
        append_foam_nodes(nodes);
        append_shore_nodes(nodes);
        return nodes;
    }();
    return list;
}

const CatalogNode* find_catalog_node(const std::string& name) {
    for (const auto& n : node_catalog())
        if (n.name == name) return &n;
    return nullptr;
}

std::string catalog_names() {
    std::string s;
    for (const auto& n : node_catalog()) s += (s.empty() ? "" : ", ") + n.name;
    return s;
}

Graph probe_graph(const CatalogNode& node) {
    Graph g;
    std::vector<Expr> inputs;
    for (const auto& in : node.inputs) inputs.push_back(varying(g, in.name, in.type));
    RelaxedScope relaxed(g, true); // the half mode of a probe rounds every operation of the node
    g.set_output("value", node.build(g, inputs).id());
    return g;
}

} // namespace watergen
