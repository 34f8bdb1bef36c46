// Specular: the sun highlight, added after the Fresnel blend. Every node returns a scalar
// intensity; the specular choice scales it by sun_color. The sun is a directional light: L is the
// unit direction sunlight travels (000's convention), so -L points at the sun.
//
// Each node is 0 (never NaN) when the sun is at or below the horizon (-L.y <= 0, e.g. the
// harbour-at-night preset) and, for the physically based lobes, when N.L <= 0 or N.V <= 0.
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

struct SpecularInputs {
    Expr normal;     // vec3, unit N
    Expr to_eye;     // vec3, unit V
    Expr sun_travel; // vec3, unit L (direction the light travels)
    Expr fresnel;    // float in [0, 1], the Fresnel reflectance of the surface blend
};

// 000: M = 2 (V.N) N - V (the view mirrored about N); d = sat(M.(-L) 0.5 + 0.5);
// s = (1 - F) sat(-L.y) d^512 (1.8 shininess + 0.2); s += 25 s sat(shininess - 0.05).
// Range [0, (1.8 shininess + 0.2)(1 + 25 sat(shininess - 0.05))], 25.185 at shininess 0.7.
Expr specular_toman_glare(Graph& g, const SpecularInputs& in);
// pow(max(0, N.H), exponent), H = normalize(-L + V); range [0, 1].
Expr specular_blinn_phong(Graph& g, const SpecularInputs& in);
// Gold: GGX D, separable Smith-GGX masking-shadowing, Schlick F on V.H with R0 from the
// indices; radiance = D G F / (4 N.L N.V) N.L. Range [0, 1 / (pi a^3)] (a = roughness).
Expr specular_ggx_sun(Graph& g, const SpecularInputs& in);

// Building blocks, exposed for tests and the probe.
// x^s for x in [0, 1], 0 for x <= 2^-14 (see specular.cpp): never pow(0, s).
Expr specular_lobe(Expr x, Expr exponent);
// normalize(a + b), or 0 when a + b is (nearly) zero: a and b opposite.
Expr half_vector(Expr a, Expr b);
// GGX / Trowbridge-Reitz D(N.H) = a^2 / (pi (ch^2 (a^2 - 1) + 1)^2); sin2_h = 1 - ch^2, best
// given as |N x H|^2 (accurate in half precision near ch = 1).
Expr ggx_distribution(Expr n_dot_h, Expr sin2_h, Expr alpha);
Expr ggx_distribution(Expr n_dot_h, Expr alpha); // sin2_h = 1 - ch^2
// Beckmann D(ch) = exp((ch^2 - 1) / (a^2 ch^2)) / (pi a^2 ch^4); water-models.md golden
// D(1, 0.3) = 3.53677651, D(0.9, 0.3) = 0.39786114.
Expr beckmann_distribution(Expr n_dot_h, Expr alpha);

} // namespace watergen
