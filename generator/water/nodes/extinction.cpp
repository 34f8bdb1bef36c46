#include "watergen/water/nodes/extinction.h"

#include <algorithm>
#include <cmath>

#include "axis_tables.h"
#include "watergen/water/surface.h"

namespace watergen {

Expr saturated_ratio(Expr x, Expr width) {
    // Where x / width is selected, width > x >= 0. The max (2^-24, the smallest binary16
    // subnormal, so it survives half precision) only keeps the unselected branch finite.
    Expr ratio = x / max(width, 0x1p-24);
    return select(x >= width, constant(x.graph(), 1.0), saturate(ratio));
}

// A distance the extinction models can use. Negative distances (a scene point a hair above the
// plane) mean no water: they would make transmittance exceed 1. Distances are capped at 30 km
// (depth + path stays below binary16's 65504), where exp(-k d) is 0 for any k above 3e-3 / m:
// an infinite distance times a zero coefficient would otherwise be NaN.
Expr water_distance(Expr d) {
    return clamp(d, 0.0, 3.0e4);
}

Expr extinction_none(Graph& g, const ExtinctionInputs& in) {
    OriginScope scope(g, "extinction.none");
    return in.refraction;
}

Expr extinction_linear(Graph& g, const ExtinctionInputs& in) {
    OriginScope scope(g, "extinction.linear");
    // 000: "extinction = [4.5; 75.0; 300.0]", the depths (m) at which r, g, b die out in clear
    // water.
    Expr ext = uniform(g, {.name = "extinction_distances",
                           .type = Type::Vec3,
                           .default_value = {4.5, 75.0, 300.0},
                           .max = 1e6,
                           .unit = "m",
                           .seed = "000"});
    // 000 names visibility, surfaceColor and depthColor without giving values; chosen: 4 m of
    // horizontal visibility, a clear blue-green surface colour, a dark blue deep colour.
    Expr visibility = uniform(g, {.name = "extinction_visibility",
                                  .type = Type::Float,
                                  .default_value = {4.0},
                                  .max = 1e6,
                                  .unit = "m",
                                  .seed = "000"});
    Expr surface_color = uniform(g, {.name = "extinction_surface_color",
                                     .type = Type::Vec3,
                                     .default_value = {0.0078, 0.5176, 0.7},
                                     .max = 1.0,
                                     .seed = "000"});
    Expr deep_color = uniform(g, {.name = "extinction_deep_color",
                                  .type = Type::Vec3,
                                  .default_value = {0.0039, 0.00196, 0.145},
                                  .max = 1.0,
                                  .seed = "000"});
    Expr depth = water_distance(in.depth);
    Expr path = water_distance(in.path);
    Expr horizontal = named(saturated_ratio(path, visibility), "visibility_fade");
    Expr vertical = named(vec3(saturated_ratio(depth, ext.x()), saturated_ratio(depth, ext.y()),
                               saturated_ratio(depth, ext.z())),
                          "depth_fade");
    Expr r1 = named(mix(in.refraction, surface_color, horizontal), "surface_tinted");
    return named(mix(r1, deep_color, vertical), "water_color");
}

Expr extinction_exponential(Graph& g, const ExtinctionInputs& in) {
    OriginScope scope(g, "extinction.exponential");
    // 002: "float a = exp(-d*k); newrefrcol = watercol + a*(refrcol-watercol);"
    Expr k = uniform(g, {.name = "extinction_density",
                         .type = Type::Float,
                         .default_value = {0.5},
                         .max = 100.0,
                         .unit = "1/m",
                         .seed = "002"});
    Expr water = uniform(g, {.name = "extinction_water_color",
                             .type = Type::Vec3,
                             .default_value = {0.0, 0.2, 0.1},
                             .max = 1.0,
                             .seed = "002"});
    // d is 002's "length from surface to bottom" along the ray: our water path.
    Expr a = named(exp(-k * water_distance(in.path)), "fog_transmittance");
    return named(water + a * (in.refraction - water), "water_color");
}

Expr extinction_absorb_scatter(Graph& g, const ExtinctionInputs& in) {
    OriginScope scope(g, "extinction.absorb_scatter");
    // 003, tropical ocean: K = (0.46, 0.09, 0.06), b = 0.11, scatter = (0.05, 0.05, 0.10).
    Expr k = uniform(g, {.name = "absorb_coefficients",
                         .type = Type::Vec3,
                         .default_value = {0.46, 0.09, 0.06},
                         .max = 100.0,
                         .unit = "1/m",
                         .seed = "003"});
    Expr b = uniform(g, {.name = "scatter_coefficient",
                         .type = Type::Float,
                         .default_value = {0.11},
                         .max = 100.0,
                         .unit = "1/m",
                         .seed = "003"});
    Expr scatter = uniform(g, {.name = "scatter_color",
                               .type = Type::Vec3,
                               .default_value = {0.05, 0.05, 0.10},
                               .max = 1.0,
                               .seed = "003"});
    // 003: "WorldUnitsToMeters" scales K and b once for the game world.
    Expr scale = uniform(g, {.name = "world_to_meters",
                             .type = Type::Float,
                             .default_value = {1.0},
                             .min = 1e-6,
                             .max = 1e6,
                             .unit = "m/unit",
                             .seed = "003"});
    Expr light = uniform(g, {.name = "incident_light",
                             .type = Type::Vec3,
                             .default_value = {1.0, 1.0, 1.0},
                             .max = 1e3,
                             .seed = "003"});
    Expr depth = water_distance(in.depth);
    Expr path = water_distance(in.path);
    Expr transmittance = named(exp(-(k * scale) * (depth + path)), "transmittance");
    Expr inverse_scatter = named(exp(-(b * scale) * path), "inverse_scatter");
    return named(mix(scatter, in.refraction * transmittance, inverse_scatter) * light,
                 "water_color");
}

Expr extinction_beer_lambert(Graph& g, const ExtinctionInputs& in) {
    OriginScope scope(g, "extinction.beer_lambert");
    // Pope and Fry (1997), pure water absorption at 650 / 550 / 450 nm (r, g, b).
    Expr a = uniform(g, {.name = "extinction_pure_water_absorption",
                         .type = Type::Vec3,
                         .default_value = {0.340, 0.0565, 0.00922},
                         .max = 100.0,
                         .unit = "1/m",
                         .seed = "Pope and Fry 1997"});
    // Light goes down to the bed (depth) and back up along the view ray (path).
    Expr distance = named(water_distance(in.depth) + water_distance(in.path), "water_distance");
    return named(in.refraction * exp(-a * distance), "water_color");
}

namespace {

// Sunlight left after `depth` m of water absorbing at least `k` per m, Beer-Lambert's exp(-k d)
// (SceneFact::BottomLit). Only the way down counts: the view path back up is not bounded below
// where refraction distorts the scene lookup.
double transmitted(double k, double depth) {
    return std::exp(-std::max(k, 0.0) * depth);
}

double linear_sunlight(const ParameterBounds& bounds, double depth) {
    // 000: the bottom fades linearly into the deep colour and is gone at extinction_distances.
    const double reach = bounds("extinction_distances").second;
    return reach > 0.0 ? std::max(0.0, 1.0 - depth / reach) : 0.0;
}

double exponential_sunlight(const ParameterBounds& bounds, double depth) {
    return transmitted(bounds("extinction_density").first, depth);
}

double absorb_scatter_sunlight(const ParameterBounds& bounds, double depth) {
    return transmitted(bounds("absorb_coefficients").first * bounds("world_to_meters").first,
                       depth);
}

double beer_lambert_sunlight(const ParameterBounds& bounds, double depth) {
    return transmitted(bounds("extinction_pure_water_absorption").first, depth);
}

// A choice whose node turns the refracted colour into the water colour.
ChoiceInfo extinction_choice(ChoiceInfo info, Expr (*node)(Graph&, const ExtinctionInputs&),
                             SunlightAtDepth sunlight = {}) {
    info.sunlight_at_depth = std::move(sunlight);
    return feature_choice(
        std::move(info),
        {{"depth", Type::Float}, {"path", Type::Float}, {"refraction", Type::Vec3}}, node,
        [node](Surface& s) {
            s.water_color = node(s.g, {s.depth, s.path, s.refracted});
        });
}

} // namespace

AxisInfo extinction_axis() {
    // exponential and absorb_scatter are Beer-Lambert's exp(-k d) with artistic coefficients
    // (one grey density; 003's ocean K plus scatter), measured against the pure-water gold.
    return {
        "extinction",
        "absorb_scatter",
        {
            extinction_choice({.name = "none", .description = "refracted colour unchanged"},
                              &extinction_none),
            extinction_choice(
                {.name = "linear",
                 .seed = "000",
                 .description =
                     "per-channel linear fades with depth and with horizontal visibility"},
                &extinction_linear, &linear_sunlight),
            extinction_choice(
                {.name = "exponential",
                 .seed = "002",
                 .description = "exponential fog towards the water colour, a = exp(-d k)",
                 .approximates = "beer_lambert"},
                &extinction_exponential, &exponential_sunlight),
            extinction_choice({.name = "absorb_scatter",
                               .seed = "003",
                               .description = "exponential absorption plus scatter colour",
                               .approximates = "beer_lambert"},
                              &extinction_absorb_scatter, &absorb_scatter_sunlight),
            extinction_choice(
                {.name = "beer_lambert",
                 .description = "physical per-channel absorption of pure water (Pope and Fry 1997)",
                 .gold = true},
                &extinction_beer_lambert, &beer_lambert_sunlight),
        }};
}

} // namespace watergen
