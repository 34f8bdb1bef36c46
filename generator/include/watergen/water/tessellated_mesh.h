// The tessellated mesh path (issue 28): the grid drawn as quad patches whose factors follow the
// distance to the eye, displaced in the evaluation stage by the mesh path's own vertex graph.
// Four DSL graphs, one per stage; ir/tessellation_emitter.h writes the patch stages.
#pragma once

#include <string>

#include "watergen/ir/ir.h"

namespace watergen {

// The largest factor the control stage writes: the smallest maxTessellationGenerationLevel
// Vulkan guarantees (and lavapipe's), so no draw generates more than a device allows.
constexpr double kMaxTessellationFactor = 64.0;

struct TessellatedMeshShader {
    std::string wave_model; // "sum_of_sines" or "gerstner"
    // Attribute grid_xz (vec2); outputs grid_xz (passed through, location 0) and position
    // (the undisplaced point at y = 0, read by no later stage). Reads no parameter.
    Graph patch_vertex;
    // Varyings corner_0 .. corner_3 (the patch's grid points); outputs outer_0 .. outer_3 and
    // inner_0, inner_1. Each edge's factor is tess_scale / (distance from eye_position to the
    // edge's midpoint at water_level), clamped to [1, tess_max], and tess_max itself to
    // [1, kMaxTessellationFactor]: whatever the block holds, every factor is in [1, 64]. An
    // inner factor is the larger of the two edges across it, so the patch is at least as fine
    // inside as at its finer edge; a shared edge has the same midpoint on both of its patches,
    // hence the same factor and no crack.
    Graph control;
    // build_mesh_shader(wave_model)'s vertex graph as it is: its Varying grid_xz becomes the
    // point interpolated over the patch.
    Graph evaluation;
    Graph fragment; // build_mesh_shader(wave_model)'s
};

// Parameters of the control stage besides the mesh's eye_position and water_level: tess_scale
// (m, default 40: factor 1 at 40 m, 4 at 10 m) and tess_max (default 16, range [1, 64]).
// An unknown model records a diagnostic on the evaluation graph.
TessellatedMeshShader build_tessellated_mesh_shader(const std::string& wave_model);

} // namespace watergen
