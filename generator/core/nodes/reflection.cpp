#include "watergen/nodes/reflection.h"
#include "watergen/node_catalog.h"
#include "watergen/surface.h"

namespace watergen {

Parameter sky_color() {
    return {"sky_color", Type::Vec3, {0.55, 0.7, 0.9}, 0.0, 1e3, "", "000", ""};
}

void apply_reflection(Surface& s, const std::string& choice) {
    OriginScope scope(s.g, "reflection." + choice);
    if (choice == "none") {
        s.reflected = uniform(s.g, sky_color());
        return;
    }
    s.g.error("reflection: no node for choice '" + choice + "'");
}

void append_reflection_nodes(std::vector<CatalogNode>&) {}

} // namespace watergen
