#include "watergen/nodes/waves.h"
#include "watergen/node_catalog.h"
#include "watergen/surface.h"

namespace watergen {

void apply_waves(Surface& s, const std::string& choice) {
    OriginScope scope(s.g, "waves." + choice);
    if (choice == "flat") {
        const PlaneHit hit = intersect_plane(s, s.level);
        s.surface_point = hit.point;
        set_water_column(s, hit.distance);
        return;
    }
    s.g.error("waves: no node for choice '" + choice + "'");
}

void append_waves_nodes(std::vector<CatalogNode>&) {}

} // namespace watergen
