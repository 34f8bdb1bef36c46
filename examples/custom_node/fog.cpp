// Distance fog, a whole new axis a project adds without editing watergen (seed 004 names it as
// a next step). Composed right after the shore: the water and the scene seen past it alike fade
// towards the fog colour with their distance from the eye.
//
//   fog=none         no fog (the default: every variant without fog reads as before)
//   fog=exponential  gold: a homogeneous medium's transmittance, exp(-density * distance)
//   fog=rational     1 / (1 + x + x^2 / 2) with x = density * distance: no transcendental,
//                    the first terms of exp(x) in the denominator; approximates exponential
#include "watergen/water/axis_registry.h"
#include "watergen/water/surface.h"

namespace {

using namespace watergen;

// The fog's parameters: defaults and ranges travel with the node, so materials, presets and
// scene files can set them by name like watergen's own.
Parameter fog_color() {
    return {.name = "fog_color",
            .type = Type::Vec3,
            .default_value = {0.62, 0.70, 0.78},
            .max = 1e3,
            .seed = "004"};
}
Parameter fog_density() {
    return {.name = "fog_density",
            .type = Type::Float,
            .default_value = {0.004},
            .max = 10.0,
            .unit = "1/m",
            .seed = "004"};
}

struct FogInputs {
    Expr color;    // vec3, what the eye sees there before the fog
    Expr distance; // float, m from the eye
};

Expr fog_exponential(Graph& g, FogInputs in) {
    Expr x = named(uniform(g, fog_density()) * max(in.distance, 0.0), "fog_depth");
    return named(mix(uniform(g, fog_color()), in.color, exp(-x)), "fogged");
}

Expr fog_rational(Graph& g, FogInputs in) {
    Expr x = named(uniform(g, fog_density()) * max(in.distance, 0.0), "fog_depth");
    Expr transmittance = named(1.0 / (1.0 + x * (1.0 + 0.5 * x)), "fog_transmittance");
    return named(mix(uniform(g, fog_color()), in.color, transmittance), "fogged");
}

// What a fog choice does to the surface: the water at the surface point, the scene beyond it
// (what a pixel without water shows) at its own distance.
void compose_fog(Surface& s, Expr (*node)(Graph&, FogInputs)) {
    Expr water_distance;
    {
        // Positions reach 1e5 m, beyond binary16: the distance stays 32-bit under precision=half.
        FullPrecisionScope geometry(s.g);
        water_distance = named(length(s.surface_point - s.eye), "water_distance");
    }
    s.color = node(s.g, {s.color, water_distance});
    s.scene_rgb = node(s.g, {s.scene_rgb, s.scene_distance});
}

ChoiceInfo fog_choice(ChoiceInfo info, Expr (*node)(Graph&, FogInputs)) {
    return feature_choice(std::move(info), {{"color", Type::Vec3}, {"fog_distance", Type::Float}},
                          node, [node](Surface& s) { compose_fog(s, node); });
}

} // namespace

WATERGEN_REGISTER_NODES(register_fog) {
    watergen::register_axis({
        .name = "fog",
        .default_choice = "none",
        .choices =
            {
                {.name = "none", .description = "no fog"},
                fog_choice({.name = "exponential",
                            .seed = "004",
                            .description = "distance fog, transmittance exp(-density * distance)",
                            .gold = true},
                           &fog_exponential),
                fog_choice({.name = "rational",
                            .seed = "004",
                            .description = "distance fog, transmittance 1 / (1 + x + x^2/2)",
                            .approximates = "exponential"},
                           &fog_rational),
            },
        .compose_after = "shore",
    });
}
