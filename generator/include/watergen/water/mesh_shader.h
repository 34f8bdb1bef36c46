// The mesh path: a wave model displacing an N x N grid in a vertex stage, with its analytic
// normal interpolated to a small fragment stage (N.L shading tinted by the normal). Both
// stages are DSL graphs; the wave math is the same node functions as the post-process pass.
#pragma once

#include <string>

#include "watergen/ir/dsl.h"
#include "watergen/ir/ir.h"

namespace watergen {

struct MeshShader {
    std::string wave_model; // "sum_of_sines" or "gerstner"
    // Attribute grid_xz (vec2, undisplaced grid point, m); outputs position (vec4, Vulkan clip
    // space), normal (vec3, unit) and world (vec3, displaced point, m).
    Graph vertex;
    // Varyings v_normal, v_world; output color (vec4). Reads no uniforms, so the vertex
    // stage's parameter block is the pipeline's only one.
    Graph fragment;
};

// Camera parameters of the vertex stage: eye_position, mesh_camera_right / _up / _forward
// (unit), mesh_projection (1 / (tan(fov_y / 2) aspect), 1 / tan(fov_y / 2)), mesh_near (m).
// An unknown model records a diagnostic on the vertex graph.
MeshShader build_mesh_shader(const std::string& wave_model);

// The vertex stage's eye_position (m) and water_level (m) parameters, read in `g`: another
// stage of a mesh pipeline (the tessellated path's control stage) declares them the same way.
Expr mesh_eye_position(Graph& g);
Expr mesh_water_level(Graph& g);

} // namespace watergen
