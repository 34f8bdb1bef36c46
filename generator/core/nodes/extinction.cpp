#include "watergen/nodes/extinction.h"

#include <tuple>

#include "watergen/node_catalog.h"
#include "watergen/surface.h"

namespace watergen {

Expr extinction_none(Graph& g, const ExtinctionInputs& in) {
    OriginScope scope(g, "extinction.none");
    return in.refraction;
}

Expr extinction_absorb_scatter(Graph& g, const ExtinctionInputs& in) {
    OriginScope scope(g, "extinction.absorb_scatter");
    // 003, tropical ocean: K = (0.46, 0.09, 0.06), b = 0.11, scatter = (0.05, 0.05, 0.10).
    Expr k = uniform(g, {"absorb_coefficients", Type::Vec3, {0.46, 0.09, 0.06}, 0.0, 100.0, "1/m", "003", ""});
    Expr b = uniform(g, {"scatter_coefficient", Type::Float, {0.11}, 0.0, 100.0, "1/m", "003", ""});
    Expr scatter = uniform(g, {"scatter_color", Type::Vec3, {0.05, 0.05, 0.10}, 0.0, 1.0, "", "003", ""});
    // 003: "WorldUnitsToMeters" scales K and b once for the game world.
    Expr scale = uniform(g, {"world_to_meters", Type::Float, {1.0}, 1e-6, 1e6, "m/unit", "003", ""});
    Expr light = uniform(g, {"incident_light", Type::Vec3, {1.0, 1.0, 1.0}, 0.0, 1e3, "", "003", ""});
    // Negative distances (a scene point a hair above the plane) would make S > 1 and push the
    // colour below zero: the model is only defined for paths >= 0.
    Expr depth = max(in.depth, 0.0);
    Expr path = max(in.path, 0.0);
    Expr transmittance = named(exp(-(k * scale) * (depth + path)), "transmittance");
    Expr inverse_scatter = named(exp(-(b * scale) * path), "inverse_scatter");
    return named(mix(scatter, in.refraction * transmittance, inverse_scatter) * light, "water_color");
}

void append_extinction_nodes(std::vector<CatalogNode>& list) {
    for (auto [name, f, what] : {std::tuple{"extinction.none", &extinction_none, "refracted colour unchanged"},
                                 std::tuple{"extinction.absorb_scatter", &extinction_absorb_scatter, "003 absorption + scatter"}})
        list.push_back({name, what, {{"depth", Type::Float}, {"path", Type::Float}, {"refraction", Type::Vec3}},
                        [f](Graph& g, const std::vector<Expr>& in) { return f(g, {in[0], in[1], in[2]}); }});
}

void apply_extinction(Surface& s, const std::string& choice) {
    const ExtinctionInputs in{s.depth, s.path, s.refracted};
    if (choice == "none") s.water_color = extinction_none(s.g, in);
    else if (choice == "absorb_scatter") s.water_color = extinction_absorb_scatter(s.g, in);
    else s.g.error("extinction: no node for choice '" + choice + "'");
}

} // namespace watergen
