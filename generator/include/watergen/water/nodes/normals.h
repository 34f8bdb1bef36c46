// normals: the choices of the normals axis (water/nodes/normals.cpp declares them).
#pragma once

#include "watergen/ir/core/dsl.h"

namespace watergen {

// The exact normal of a height field with slope (dh/dx, dh/dz): normalize(-dh/dx, 1, -dh/dz).
// "analytic" applies it to the wave model's wave_slope.
Expr normal_from_slope(Graph& g, Expr slope);

// Texture "detail_normal_map": tangent-space unit normals encoded to [0, 1] (rgb = 0.5 n + 0.5,
// decoded as 2 texel - 1, as 000 does); x along +u, y along +v, z along the surface normal.
// Periodic tile, texel k at k / (n - 1) like the height map (see tile_coordinate).
TextureInput detail_normal_map_texture();

// Schuler's derivative tangent frame (000, "Normal mapping without precomputed tangents"):
// unit world-space directions of increasing u and v from ddx/ddy of position and uv. `valid`
// is false where the uv derivatives vanish (or the position's do): the frame is undefined.
struct TangentFrame {
    Expr tangent, binormal; // vec3
    Expr valid;             // bool
};
TangentFrame derivative_tangent_frame(Graph& g, Expr position, Expr uv);

// 000: the detail normal map sampled twice at position.xz (two scales, each scrolling with
// time) perturbs `base` in the derivative tangent frame of the first layer. Parameters:
// detail_scale (layer scales, 1/m), detail_scroll (layer velocities, tiles/s), detail_strength,
// detail_texels, detail_max_footprint (a layer fades to flat as one pixel spans this much of a
// tile: the band limit of a map without mip levels). Falls back to `base` where the frame is
// degenerate or the decoded texels sum to a zero vector.
Expr detail_normal(Graph& g, Expr base, Expr position, Expr time);

} // namespace watergen
