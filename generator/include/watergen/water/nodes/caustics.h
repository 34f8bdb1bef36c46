// Caustics: the light the waves focus onto the bottom, seen through the water. Each choice
// scales the refracted colour (the bottom) by mix(1, I, caustics_strength), I the caustics
// intensity at the bottom point (1: the light of flat water).
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

// "caustics_tile": a periodic caustics tile, intensity in r; texel k at k / (n - 1) like the
// height map (tile_coordinate), caustics_tile_texels per side (Crest's stand-in texture).
TextureInput caustics_tile_texture();
// "caustics_map": the caustics pass's output (caustics_pass.h), intensity in r, texel (i, j)
// over the bottom window caustics_window, caustics_map_texels per side.
TextureInput caustics_map_texture();

// caustics_window (vec3: x0, z0, size of the bottom window the map covers, m): the caustics
// pass's parameter (caustics_pass.cpp declares it from here), so one uniform set drives both.
Parameter caustics_window();
// caustics_map_texels (the map's side in texels): photon_splat's filter reads it; the build's
// draw description of the pass takes the map's size from it.
Parameter caustics_map_texels();

// The inputs of each choice's catalog node ("color" and "xz" there).
struct CausticsInputs {
    Expr refracted; // vec3, the bottom seen through the water
    Expr bottom_xz; // vec2, the bottom point under it (the scene position's xz), m
};

// mix(1, intensity, caustics_strength) times the refracted colour.
Expr caustics_lit(Graph& g, Expr refracted, Expr intensity);

// The intensity of each choice at the bottom point xz (m).
// texture (Crest): the tile, repeated every caustics_tile_size m.
Expr caustics_texture_intensity(Graph& g, Expr bottom_xz);
// area_ratio (HDRP): the map's texel under the point (bilinear), 1 outside the window.
Expr caustics_area_ratio_intensity(Graph& g, Expr bottom_xz);
// photon_splat (seed 002): the map under a 4-tap box at +-0.5 texel (a 3x3 tent with the
// bilinear sampler): photon maps are noisy, the seed filters its 256x256 one. 1 outside.
Expr caustics_photon_splat_intensity(Graph& g, Expr bottom_xz);

} // namespace watergen
