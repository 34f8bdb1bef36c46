// Extinction: what the water column does to the refracted colour.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

struct ExtinctionInputs {
    Expr depth;      // vertical water depth under the surface point, m
    Expr path;       // water path length along the view ray (the seeds' "accumulated water"), m
    Expr refraction; // vec3 colour seen through the surface
};

// Refracted colour unchanged (axis choice "none").
Expr extinction_none(Graph& g, const ExtinctionInputs& in);
// 003: T = exp(-K (depth + path)), S = exp(-b path), colour = mix(scatter, refr T, S) E.
Expr extinction_absorb_scatter(Graph& g, const ExtinctionInputs& in);

} // namespace watergen
