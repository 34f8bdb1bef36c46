#include "watergen/water/nodes/shore.h"
#include "watergen/water/node_catalog.h"
#include "watergen/water/surface.h"

namespace watergen {

Expr shore_soft(Graph& g, Expr color, Expr refracted, Expr depth) {
    OriginScope scope(g, "shore.soft");
    // 000: blend back to the refracted scene near the shore; hardness 1 by default.
    Expr hardness = uniform(g, {"shore_hardness", Type::Float, {1.0}, 0.0, 1e3, "1/m", "000", ""});
    return named(mix(refracted, color, saturate(max(depth, 0.0) * hardness)), "shore_color");
}

void apply_shore(Surface& s, const std::string& choice) {
    if (choice == "hard") return;
    if (choice == "soft") {
        s.color = shore_soft(s.g, s.color, s.refracted, s.depth);
        return;
    }
    s.g.error("shore: no node for choice '" + choice + "'");
}

void append_shore_nodes(std::vector<CatalogNode>&) {}

} // namespace watergen
