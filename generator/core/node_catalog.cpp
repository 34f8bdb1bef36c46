#include "watergen/node_catalog.h"

#include "watergen/nodes.h"

namespace watergen {

namespace {

CatalogNode fresnel(const char* name, Expr (*f)(Graph&, Expr), const char* what) {
    return {name, what, {{"c", Type::Float}}, [f](Graph& g, const std::vector<Expr>& in) { return f(g, in[0]); }};
}

CatalogNode extinction(const char* name, Expr (*f)(Graph&, const ExtinctionInputs&), const char* what) {
    return {name, what, {{"depth", Type::Float}, {"path", Type::Float}, {"refraction", Type::Vec3}},
            [f](Graph& g, const std::vector<Expr>& in) { return f(g, {in[0], in[1], in[2]}); }};
}

} // namespace

const std::vector<CatalogNode>& node_catalog() {
    static const std::vector<CatalogNode> list = {
        fresnel("fresnel.none", fresnel_none, "constant reflectance"),
        fresnel("fresnel.schlick", fresnel_schlick, "Schlick reflectance of cos(theta) c"),
        fresnel("fresnel.exact", fresnel_exact, "exact unpolarised reflectance of cos(theta) c, with TIR"),
        extinction("extinction.none", extinction_none, "refracted colour unchanged"),
        extinction("extinction.absorb_scatter", extinction_absorb_scatter, "003 absorption + scatter"),
    };
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
    g.set_output("value", node.build(g, inputs).id());
    return g;
}

} // namespace watergen
