#include "watergen/nodes/normals.h"
#include "watergen/node_catalog.h"
#include "watergen/surface.h"

namespace watergen {

void apply_normals(Surface& s, const std::string& choice) {
    OriginScope scope(s.g, "normals." + choice);
    if (choice == "flat") {
        s.normal = constant(s.g, {0.0, 1.0, 0.0});
        return;
    }
    s.g.error("normals: no node for choice '" + choice + "'");
}

void append_normals_nodes(std::vector<CatalogNode>&) {}

} // namespace watergen
