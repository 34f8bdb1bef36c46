#include "watergen/nodes/specular.h"
#include "watergen/node_catalog.h"
#include "watergen/surface.h"

namespace watergen {

void apply_specular(Surface& s, const std::string& choice) {
    OriginScope scope(s.g, "specular." + choice);
    if (choice == "none") {
        s.specular = constant(s.g, {0.0, 0.0, 0.0});
        return;
    }
    s.g.error("specular: no node for choice '" + choice + "'");
}

void append_specular_nodes(std::vector<CatalogNode>&) {}

} // namespace watergen
