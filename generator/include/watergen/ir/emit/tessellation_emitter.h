// The patch stages of the tessellated mesh path (issue 28): tessellation control (GLSL tesc,
// HLSL hull with its patch-constant function) and tessellation evaluation (GLSL tese, HLSL
// domain), written from DSL graphs into skeletons like the vertex stage (vertex_emitter.h).
//
// The patch is a quad of 4 control points, corners (u, v) = (0, 0), (1, 0), (0, 1), (1, 1) in
// that order, each carrying the undisplaced grid point grid_xz (vec2, location 0). Both
// languages state the same domain: quads, fractional_odd spacing, clockwise triangles (GLSL on
// the evaluation stage, HLSL on the hull as its attributes require).
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include "watergen/ir/emit/emitter.h"

namespace watergen {

struct PatchStageOptions {
    const BindingMap* bindings = nullptr;
    // The parameter block both patch stages declare (shared_block_parameters of the pipeline's
    // graphs): they bind one uniform buffer, so each declares the same members at the same
    // offsets whatever it reads. Null: the parameters the graph reads (a pipeline where one
    // stage alone reads parameters).
    const std::vector<Parameter>* block = nullptr;
};

// Tessellation control from `g` into templates/<language>/<skeleton>.tesc.<ext>. The skeleton
// defines the Varyings corner_0 .. corner_3 (vec2: the control points' grid_xz, corners in the
// order above) and passes each control point through; `g` may read no other Varying. Required
// float outputs: outer_0 .. outer_3 (the edges u = 0, v = 0, u = 1, v = 1, as GLSL's
// gl_TessLevelOuter and HLSL's SV_TessFactor number them) and inner_0, inner_1 (the u and v
// directions). The graph's own clamps bound them: the skeleton writes what it computes.
EmittedShader emit_tess_control(const Graph& g, Language language, const std::string& skeleton,
                                const std::string& file_name, const std::string& variant_key,
                                Diagnostics& diagnostics, const PatchStageOptions& options = {});

// Tessellation evaluation from `g` into templates/<language>/<skeleton>.tese.<ext>. The
// skeleton defines the Varying grid_xz (vec2) as the bilinear interpolation of the 4 control
// points at the tessellation coordinate (GLSL gl_TessCoord.xy, HLSL SV_DomainLocation), so a
// mesh vertex graph (build_mesh_shader's) serves as it is; `g` may read no other Varying. The
// output "position" (vec4, clip space) is required; every other output must be one the
// skeleton writes.
EmittedShader emit_tess_evaluation(const Graph& g, Language language, const std::string& skeleton,
                                   const std::string& file_name, const std::string& variant_key,
                                   Diagnostics& diagnostics, const PatchStageOptions& options = {});

// The parameters any of `graphs` reads, each once, in the order the graphs (then their
// declarations) give: the block every stage of a pipeline declares. One name declared with two
// definitions (same_definition) is an error naming both.
std::vector<Parameter> shared_block_parameters(const std::vector<const Graph*>& graphs,
                                               Diagnostics& diagnostics);

} // namespace watergen
