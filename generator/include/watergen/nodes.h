// Feature nodes: the water models of the seed articles (../shared/docs/water-models.md), each
// written once against the DSL. A node declares the parameters it reads (with unit, default,
// valid range and seed) through uniform(); the composed shader declares only what it uses.
#pragma once

#include "watergen/dsl.h"

namespace watergen {

// --- Fresnel: reflectance for c = cos(angle between unit normal and unit view vector) -----

// Constant reflectance `fresnel_constant` (axis choice "none").
Expr fresnel_none(Graph& g, Expr c);
// 000: Schlick, F = R0 + (1 - R0)(1 - c)^5 with R0 = ((n1 - n2) / (n1 + n2))^2.
Expr fresnel_schlick(Graph& g, Expr c);
// Gold: unpolarised dielectric reflectance with total internal reflection (R = 1).
Expr fresnel_exact(Graph& g, Expr c);

// --- Extinction: what the water does to the refracted colour ------------------------------

struct ExtinctionInputs {
    Expr depth;      // vertical water depth under the surface point, m
    Expr path;       // water path length along the view ray (the seeds' "accumulated water"), m
    Expr refraction; // vec3 colour seen through the surface
};

// Refracted colour unchanged (axis choice "none").
Expr extinction_none(Graph& g, const ExtinctionInputs& in);
// 003: T = exp(-K (depth + path)), S = exp(-b path), colour = mix(scatter, refr T, S) E.
Expr extinction_absorb_scatter(Graph& g, const ExtinctionInputs& in);

// Shared parameters.
Parameter ior_air();
Parameter ior_water();

} // namespace watergen
