// Extinction: what the water column does to the refracted colour.
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

struct ExtinctionInputs {
    Expr depth;      // vertical water depth under the surface point, m
    Expr path;       // water path length along the view ray (the seeds' "accumulated water"), m
    Expr refraction; // vec3 colour seen through the surface
};

// Clamps a water distance to [0, 30 km] (see extinction.cpp for why).
Expr water_distance(Expr d);

// Refracted colour unchanged (axis choice "none").
Expr extinction_none(Graph& g, const ExtinctionInputs& in);
// 000: r1 = mix(refr, surface_color, sat(path / visibility));
//      colour = mix(r1, deep_color, sat(depth / ext)), ext = (4.5, 75, 300) m per channel.
// Zero visibility or a zero extinction distance means "opaque": the blend factor is 1 for any
// distance, and no division by zero is ever evaluated.
Expr extinction_linear(Graph& g, const ExtinctionInputs& in);
// 002: a = exp(-k path), colour = water_color + a (refr - water_color), k = 0.5 1/m.
Expr extinction_exponential(Graph& g, const ExtinctionInputs& in);
// 003: T = exp(-K (depth + path)), S = exp(-b path), colour = mix(scatter, refr T, S) E.
Expr extinction_absorb_scatter(Graph& g, const ExtinctionInputs& in);
// Gold: pure-water absorption (Pope and Fry 1997) a = (0.340, 0.0565, 0.00922) 1/m at
// 650/550/450 nm; colour = refr exp(-a (depth + path)).
Expr extinction_beer_lambert(Graph& g, const ExtinctionInputs& in);

// sat(x / width) for x, width >= 0 that never divides by zero: 1 once x >= width (so a zero
// width is a hard step at 0, "opaque"), x / width only where 0 <= x < width, i.e. width > 0.
Expr saturated_ratio(Expr x, Expr width);

} // namespace watergen
