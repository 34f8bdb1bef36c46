#include "watergen/water/node_catalog.h"

#include "watergen/ir/core/identifier.h"
#include "watergen/ir/core/text.h"
#include "watergen/water/axis_registry.h"

namespace watergen {

const std::vector<CatalogNode>& node_catalog() {
    static const std::vector<CatalogNode> list = [] {
        std::vector<CatalogNode> nodes;
        for (const auto& a : axes()) {
            for (const auto& c : a.choices) {
                if (!c.node) continue;
                const std::string note = c.node->note.empty() ? "" : "; " + c.node->note;
                nodes.push_back(
                    {a.name + "." + c.name, c.description + note, c.node->inputs, c.node->build,
                     c.approximates.empty() ? "" : a.name + "." + c.approximates, c.author});
            }
            nodes.insert(nodes.end(), a.extra_nodes.begin(), a.extra_nodes.end());
        }
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
    return join(node_catalog(), [](const CatalogNode& n) { return n.name; });
}

Graph probe_graph(const CatalogNode& node) {
    Graph g;
    AuthorScope author(g, node.author);
    OriginScope origin(g, node.author.builtin() ? "" : node.name);
    std::vector<Expr> inputs;
    for (const auto& in : node.inputs) {
        if (auto problem = identifier_problem(in.name)) g.error("node input: " + *problem);
        inputs.push_back(varying(g, in.name, in.type));
    }
    RelaxedScope relaxed(g, true); // the half mode of a probe rounds every operation of the node
    g.set_output("value", node.build(g, inputs).id());
    return g;
}

} // namespace watergen
