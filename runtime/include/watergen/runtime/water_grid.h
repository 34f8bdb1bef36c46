// The camera-centred grid an engine draws displaced water with (the geometry axis' mesh and
// tessellated choices: generator/include/watergen/water/mesh_shader.h): a geometry clipmap of
// square rings, each level twice as coarse as the one inside it, whose vertices the vertex
// stage morphs onto the next coarser level's grid near the ring's outer edge, so neighbouring
// levels meet without cracks. CPU only (standard library); part of watergen::runtime.
//
// Level k (0 = finest) has spacing h_k = spacing 2^k and its centre snapped per axis to
// c_k = floor(eye / (2 h_k)) 2 h_k, so every vertex of level k + 1 is a grid point of level k
// too. Level 0 is the cells [-n, n)^2 (n = ring_cells) of spacing h_0 around c_0; level k >= 1
// the cells [-n, n)^2 of spacing h_k around c_k less the hole level k - 1 covers: cells
// [o - n/2, o + n/2) per axis with o = (c_{k-1} - c_k) / h_k, 0 or 1. Together the levels tile
// the coarsest level's square exactly once.
//
// Morphing (what the vertex stage computes, water_grid_morphed() in double): d = max(|x -
// eye_x|, |z - eye_z|) / h in the vertex's own cells, t = clamp((d - morph_start) / (morph_end
// - morph_start), 0, 1) and the point is grid_xz + t to_coarse. morph_start = n/2 + 4 and
// morph_end = n - 3, because eye - c_k lies in [0, 2 h_k) per axis for every eye of the snap
// the grid was built for:
//  - a vertex on level k's outer edge is more than n - 2 cells from the eye, so t = 1 with a
//    cell of margin: its odd vertices sit on level k + 1's grid lines, the edge has exactly
//    level k + 1's vertices and there is no T-junction crack;
//  - a vertex on level k's inner edge (level k - 1's outer edge, whose centre c_{k-1} is within
//    [0, h_k) of the eye per axis) is less than n/2 + 1 cells away, so t = 0 with 3 cells of
//    margin: it stays put and meets level k - 1's fully morphed edge vertex for vertex.
// n >= 16 keeps morph_start < morph_end.
//
// Precision: the vertices are floats (the vertex attribute is a vec2) in the shader's frame:
// relative to the frame centre (WaterGrid::origin, frame_centre_of(eye): host_values.h), which
// the uniform writer moves the eye and every other position into too. With a dyadic spacing
// (0.5, 0.25 m, ...) every grid point and every morphed point is then exact, however far the
// eye is from the world origin (within 2^50 spacings); another spacing meets its neighbour
// level only to float rounding.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "watergen/runtime/host_values.h"

namespace watergen {

struct WaterGridDesc {
    double spacing = 0.5;     // m: the finest level's cell size, in [1e-3, 1e3]
    uint32_t ring_cells = 32; // n: each level spans [-n, n) cells of its own spacing around its
                              // centre; even, in [16, 512]
    uint32_t levels = 8;      // L, in [1, 16]
};

// Triangles: each cell (corners a = (i, j), b = (i+1, j), c = (i, j+1), d = (i+1, j+1)) is the
// triangles (a, b, c) and (b, d, c), counter-clockwise in (x, z). Patches: each cell is one
// quad patch with control points a, b, c, d in that order (the tessellated geometry).
enum class GridTopology { Triangles, Patches };

struct WaterGrid {
    // Interleaved per vertex: grid_xz (2 floats: x, z of the undisplaced point less `origin`, m)
    // then grid_lod (3 floats: to_coarse x, to_coarse z, spacing h of the vertex's level, m).
    // to_coarse is -h on an axis where the vertex is odd relative to its level's centre (the
    // next even vertex is on the coarser level's grid line), else 0. Vertices are shared
    // within a level, not across levels; levels coarsest first, each row by row (z, then x).
    std::vector<float> vertices;
    // The frame centre the vertices' grid_xz are relative to (world x, z, m): the eye's
    // frame_centre_of, the one the uniform writer uses for the eye of the same frame.
    FrameCentre origin;
    static constexpr uint32_t kFloatsPerVertex = 5; // attribute sizes {2, 3}
    // Triangles (3 per) or quad patches (4 per). Draw order, for a renderer without a depth
    // buffer where later triangles overwrite earlier ones: coarsest level first, within a level
    // cells by decreasing Chebyshev distance of the cell's centre from the eye (ties by (j, i)
    // ascending).
    std::vector<uint32_t> indices;
    GridTopology topology = GridTopology::Triangles;
    uint32_t patch_control_points = 0;     // 0 for triangles, 4 for patches
    double morph_start = 0, morph_end = 0; // in cells: uniforms grid_morph_start, grid_morph_end

    uint32_t vertex_count() const { return uint32_t(vertices.size() / kFloatsPerVertex); }
};

// The most vertices a grid may have (water_grid_error refuses more): 2^22, 80 MB of vertices
// and about as many cells, so no description makes an unbounded draw.
constexpr uint64_t kMaxWaterGridVertices = uint64_t(1) << 22;

// Why `desc` is out of range (the field, its value and the range expected, or the vertex count
// and the cap); std::nullopt when it is valid.
std::optional<std::string> water_grid_error(const WaterGridDesc& desc);

// The grid around the eye (m). Throws std::invalid_argument with water_grid_error's text for an
// invalid description, and for an eye that is not finite or farther than 2^50 spacings from the
// origin (where the snap integers would no longer be exact).
//
// The vertices (and the set of cells) change only when water_grid_snap() does, so an engine
// rebuilds and re-uploads the vertex buffer only then; the draw order follows the eye itself,
// so an engine that relies on it (no depth buffer) rebuilds the indices as the eye moves.
WaterGrid water_grid(const WaterGridDesc& desc, double eye_x, double eye_z, GridTopology topology);

// Each level's snapped centre in units of 2 h_k, finest first: the integers floor(eye / (2 h_k))
// per axis (x, z). Same errors as water_grid().
std::vector<std::array<int64_t, 2>> water_grid_snap(const WaterGridDesc& desc, double eye_x,
                                                    double eye_z);

// The vertices water_grid() makes for `desc`, without building it: (2n + 1)^2 for level 0 and
// (2n + 1)^2 - (n - 1)^2 for every other level (its square less the hole's interior vertices,
// whatever o is). Throws std::invalid_argument for a field out of range; a count over the cap
// is returned (it is what water_grid_error checks).
uint64_t water_grid_vertex_count(const WaterGridDesc& desc);

// The morphed grid point (x, z) of `vertex` as the vertex stage computes it, in double from the
// grid's floats: grid_xz + t to_coarse with t as above, in world coordinates (origin added;
// the eye too is in world coordinates). Throws std::out_of_range for a vertex
// past the grid's.
std::array<double, 2> water_grid_morphed(const WaterGrid& grid, uint32_t vertex, double eye_x,
                                         double eye_z);

} // namespace watergen
