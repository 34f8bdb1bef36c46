#include "watergen/nodes/foam.h"
#include "watergen/node_catalog.h"
#include "watergen/surface.h"

namespace watergen {

void apply_foam(Surface& s, const std::string& choice) {
    if (choice == "none") return;
    OriginScope scope(s.g, "foam." + choice);
    s.g.error("foam: no node for choice '" + choice + "'");
}

void append_foam_nodes(std::vector<CatalogNode>&) {}

} // namespace watergen
