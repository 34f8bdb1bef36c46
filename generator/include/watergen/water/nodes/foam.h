// Foam (000): how much foam covers the surface point, times a foam pattern texture, blended
// over the composed colour: colour = mix(colour, foam_color pattern, f).
#pragma once

#include <cstdint>

#include "watergen/ir/core/dsl.h"

namespace watergen {

// The pattern is a kFoamPatternSize^2 texture holding one period of a smooth periodic
// function over size - 1 texels (texel size - 1 repeats texel 0), so wrapping with fract lands
// on texel centres on both sides of the seam under the shared clamp-to-edge sampler.
constexpr uint32_t kFoamPatternSize = 256;
TextureInput foam_pattern_texture(); // "foam_pattern", value in .r, within [0.2, 1]
// The periodic pattern at (u, v) (period 1 in both): what the texture stores. A sum of sines
// with at most kFoamPatternMaxCycles cycles per period, mean kFoamPatternMean.
double foam_pattern_value(double u, double v);
constexpr double kFoamPatternMaxCycles = 5.0;
constexpr double kFoamPatternMean = 0.6;

struct FoamInputs {
    Expr color;   // vec3, the composed water colour
    Expr pattern; // float, foam texture value at the surface point
    Expr depth;   // float, water depth under the surface point, m
    Expr height;  // float, wave height at the surface point above the water level, m
};

// 000, e = foam_existence = (0.45, 4.35, 1.5) m:
// shore: f = 1 for depth < e.x, falling linearly to 0 at e.y (a step at e.x if e.y <= e.x).
Expr foam_shore_coverage(Graph& g, Expr depth);
// crest: f = sat((h - e.z) / (Hmax - e.z)); 0 when Hmax <= e.z (000: no crest foam then).
Expr foam_crest_coverage(Graph& g, Expr height);

Expr foam_shore(Graph& g, const FoamInputs& in);
Expr foam_crest(Graph& g, const FoamInputs& in);
Expr foam_both(Graph& g, const FoamInputs& in); // f = sat(shore + crest)

// Texture coordinate of the pattern for a world position (xz, m) at `time` (s), wrapped and
// mapped onto texel centres. Geometry: build it outside any RelaxedScope (half cannot hold
// 1e5 m or a day of seconds).
Expr foam_pattern_coordinate(Graph& g, Expr world_xz, Expr time);
// The sampled pattern band-limited to the pixel: faded to its mean as the pixel footprint (m,
// the larger screen derivative of the surface point) grows from 1/4 to 1/2 of the shortest
// wavelength. The texture has no mip chain; this is its one-level stand-in.
Expr foam_pattern_filtered(Graph& g, Expr pattern, Expr footprint);

} // namespace watergen
