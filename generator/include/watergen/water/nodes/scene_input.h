// Scene input: where the water pass learns the world position of the scene behind each pixel.
// Either a world-position texture the engine writes (position_texture), or the depth buffer it
// already has, unprojected through the inverse view-projection (depth_buffer). The depth
// conventions of engines differ; each is a specialization constant, so the compiler folds the
// ones an engine fixes and a wrong one is a wrong image, which the render check catches.
#pragma once

#include <array>

#include "watergen/ir/core/dsl.h"

namespace watergen {

// The depth buffer the scene pass wrote, sampled as a texture: the window depth in r (what a
// D32 / D24 depth view returns), 0 at the near plane and 1 at the far one (reversed: the other
// way round).
TextureInput scene_depth_texture();

// The conventions, each a 0/1 specialization constant (default first):
Parameter scene_depth_reversed();  // 1: reversed Z, near 1 and far 0 (the default); 0: near 0
Parameter scene_depth_gl_range();  // 1: NDC z in [-1, 1] (OpenGL); 0: [0, 1] (Vulkan, D3D)
Parameter scene_ndc_y_up();        // 1: NDC y up, uv row 0 at NDC y = +1 (D3D, GL); 0: Vulkan
Parameter scene_camera_relative(); // 1: the matrix yields positions relative to eye_position
// Depth within this of the far value is sky (the clear value: 0 matches only the clear).
Parameter scene_sky_depth_margin();
// How far along its ray a sky pixel's position lies, m (above the water: the pass leaves it).
Parameter scene_sky_distance();
// Column k of the inverse view-projection: NDC (x, y, z, 1) to world (or camera-relative)
// homogeneous position. Identity until the engine sets the camera.
Parameter scene_inv_view_proj_column(int k);

// The scene at uv from its depth: NDC from uv and the window depth by the conventions,
// through the inverse view-projection, divided by w; a sky pixel at scene_sky_distance along
// its ray. `to_scene` is the position less eye, straight from a camera-relative matrix (no
// cancellation: the float subtraction of two positions 100 m out loses 2^-24 of 100 m, which
// the water's surface hit magnifies); `position` is the world position.
struct SceneFromDepth {
    Expr position, to_scene;
};
SceneFromDepth scene_position_from_depth(Graph& g, Expr uv, Expr eye);

} // namespace watergen
