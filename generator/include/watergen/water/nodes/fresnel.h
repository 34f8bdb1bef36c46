// Fresnel: reflectance for c = cos(angle between the unit normal and the unit view vector).
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

Parameter ior_air();   // n1, the medium the eye is in (000: air, 1.0)
Parameter ior_water(); // n2 (1.33333)

// Constant reflectance `fresnel_constant` (axis choice "none").
Expr fresnel_none(Graph& g, Expr c);
// 002: F = (1 - c)^q, q = 4.5. The base is clamped to [0, 1] first (pow of a negative base is
// undefined on GPUs).
Expr fresnel_power(Graph& g, Expr c);
// 000: Schlick, F = R0 + (1 - R0)(1 - c)^5 with R0 = ((n1 - n2) / (n1 + n2))^2.
Expr fresnel_schlick(Graph& g, Expr c);
// Gold: unpolarised dielectric reflectance with total internal reflection (R = 1).
Expr fresnel_exact(Graph& g, Expr c);

} // namespace watergen
