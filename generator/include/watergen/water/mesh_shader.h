// The stages before a mesh's fragment (the geometry axis' mesh and tessellated choices): a
// wave model displacing the runtime's clipmap grid (runtime/water_grid.h) in the vertex stage,
// or in the evaluation stage of patches the control stage subdivides by distance
// (tessellated_mesh.h). Each stage is a DSL graph; the wave math is the same node functions as
// the screen pass', and the fragment stage is the water pass itself (build_water_shader), fed
// the rasterised point by mesh_fragment_inputs().
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "watergen/ir/core/dsl.h"
#include "watergen/ir/core/ir.h"

namespace watergen {

// The varyings the last stage before the fragment writes and a mesh fragment reads, in location
// order: v_world (vec3, the displaced point, m), v_grid (vec2, its undisplaced grid point, m),
// v_clip (vec4, its clip-space position).
std::vector<std::pair<std::string, Type>> mesh_fragment_inputs();

// The vertex layout of a grid (runtime/water_grid.h), attribute i at location i: grid_xz (vec2,
// the undisplaced point, m) and grid_lod (vec3: the offset to the next coarser level's grid
// point, m, and the level's spacing h, m).
std::vector<std::pair<std::string, Type>> mesh_vertex_inputs();

// The stages of one geometry ("mesh" or "tessellated") for `wave_model` (flat, sum_of_sines or
// gerstner). mesh: `vertex` only, the grid point morphed and displaced. tessellated: `vertex`
// morphs each control point (outputs position and grid_xz), `control` sets the factors and
// `evaluation` displaces the generated points. Errors go to the first graph's diagnostics.
struct MeshStages {
    std::string geometry;
    Graph vertex, control, evaluation;
    bool tessellated() const { return geometry == "tessellated"; }
    std::vector<const Graph*> graphs() const; // the stages present, in pipeline order
    std::vector<Graph*> graphs();
};
MeshStages build_mesh_stages(const std::string& geometry, const std::string& wave_model);

// The parameters every stage reads, the water pass' fragment as each mesh stage (one definition,
// one block for all stages): eye_position (m), water_level (m), time (s).
Expr scene_eye_position(Graph& g);
Expr scene_water_level(Graph& g);
Expr scene_time(Graph& g);
Expr scene_sun_direction(Graph& g); // unit, the direction the sunlight travels

// The grid point of the attributes grid_xz and grid_lod, morphed towards the coarser level's
// grid as it nears its level's outer edge: t = clamp((d / h - grid_morph_start) /
// (grid_morph_end - grid_morph_start), 0, 1) with d the larger of |x - eye.x|, |z - eye.z|
// (water_grid.h says why those bounds leave no crack). The defaults never morph (a plain grid).
Expr morphed_grid_point(Graph& g, Expr eye);

// Writes the outputs position (clip space), world, grid and clip of the point `grid` (m)
// displaced by `wave_model` into `g`. The waves are band-limited to what a pixel shows, as the
// screen pass' are, by mesh_pixel_angle (rad per pixel, 2 tan(fov_y / 2) / height; default 0:
// every wave): measured on the beach view, that limit alone beats adding the grid's own
// Nyquist limit (docs/measurements.md, "Water as geometry"), and it leaves the mesh and the
// tessellated geometry displaced alike. Clip space: camera basis mesh_camera_right / _up /
// _forward (unit), mesh_projection (1 / (tan(fov_y / 2) aspect), 1 / tan(fov_y / 2)) and
// mesh_near (m): x right, y down, z = depth - near, w = depth (an infinite projection with
// depth in [0, 1) beyond the near plane).
void displace_grid_point(Graph& g, const std::string& wave_model, Expr grid);

} // namespace watergen
