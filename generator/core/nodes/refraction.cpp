#include "watergen/nodes/refraction.h"
#include "watergen/node_catalog.h"
#include "watergen/surface.h"

namespace watergen {

void apply_refraction(Surface& s, const std::string& choice) {
    OriginScope scope(s.g, "refraction." + choice);
    if (choice == "none") {
        s.refracted = s.scene_rgb;
        return;
    }
    s.g.error("refraction: no node for choice '" + choice + "'");
}

void append_refraction_nodes(std::vector<CatalogNode>&) {}

} // namespace watergen
