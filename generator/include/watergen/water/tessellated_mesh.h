// The patch stages of the tessellated geometry (mesh_shader.h): the grid drawn as quad patches
// whose factors follow the distance to the eye; the evaluation stage displaces the generated
// points as the mesh's vertex stage does. ir/tessellation_emitter.h writes the patch stages.
#pragma once

#include "watergen/ir/core/ir.h"

namespace watergen {

// The largest factor the control stage writes: the smallest maxTessellationGenerationLevel
// Vulkan guarantees (and lavapipe's), so no draw generates more than a device allows.
constexpr double kMaxTessellationFactor = 64.0;

// The patch vertex stage into `g`: attributes grid_xz and grid_lod (mesh_vertex_inputs()), the
// grid point morphed (morphed_grid_point); outputs grid_xz (the morphed point, location 0) and
// position (the point at y = 0, read by no later stage).
void build_patch_vertex(Graph& g);

// The control stage into `g`: Varyings corner_0 .. corner_3 (the patch's morphed grid points);
// outputs outer_0 .. outer_3 and inner_0, inner_1. Each edge's factor is tess_scale / (distance
// from eye_position to the edge's midpoint at water_level), clamped to [1, tess_max], and
// tess_max itself to [1, kMaxTessellationFactor]: whatever the block holds, every factor is in
// [1, 64]. An inner factor is the larger of the two edges across it, so the patch is at least as
// fine inside as at its finer edge; a shared edge has the same midpoint on both of its patches,
// hence the same factor and no crack. tess_scale: m, default 40 (factor 1 at 40 m, 4 at 10 m);
// tess_max: default 16, range [1, 64].
void build_tess_control(Graph& g);

} // namespace watergen
