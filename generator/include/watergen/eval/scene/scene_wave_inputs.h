// Textures of the wave and normal nodes for the synthetic scene (render/scene_wave_inputs.cpp).
// Both are periodic tiles in the layout tile_coordinate() expects: texel k of n sits at tile
// coordinate k / (n - 1), so the last row and column repeat the first. Smooth and band-limited
// (at most 4 cycles per tile, >= 15 texels per cycle at n = 64) and deterministic.
#pragma once

#include <cstdint>

#include "watergen/headless/texture_data.h"

namespace watergen {

constexpr uint32_t kWaveTextureTexels = 64;

// "height_map": r = height in [-1, 1] (a sum of three tile-periodic sinusoids), g = b = 0, a = 1.
TextureData make_height_map(uint32_t texels = kWaveTextureTexels);
// "detail_normal_map": rgb = 0.5 n + 0.5 with n the unit tangent-space normal of a ripple
// height field (x along +u, y along +v, z out of the surface), a = 1.
TextureData make_detail_normal_map(uint32_t texels = kWaveTextureTexels);

} // namespace watergen
