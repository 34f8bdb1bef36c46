// A companion pass of a build as the engine draws it: a water variant with caustics=area_ratio
// or photon_splat samples caustics_map, a texture the engine fills each frame with the
// variant's caustics pass (manifest entry "passes"."caustics", files under passes/). This
// header holds what the manifest says about the pass and the grid the pass is drawn over;
// ShaderBuild::pass() (shader_build.h) hands out the pass itself. Part of watergen::runtime.
//
// The draw: clear a texels x texels target of `format` to `clear`; draw the grid (a vec2
// attribute at location 0, `attribute`) as a triangle list or a point list with blending
// ONE + ONE (every fragment's colour added); read `channel`. The grid covers the window
// (`window`, a vec3 parameter: x0, z0, size in m) grown by a margin of scale x the parameter
// `margin.parameter` + add, m, on every side (light drifts sideways on its way to the bottom).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "watergen/runtime/host_values.h"

namespace watergen {

struct PassDraw {
    std::string primitive; // "triangles" (two per grid cell) or "points" (one per cell)
    std::string attribute; // "grid_xz": the undisplaced grid point, m
    uint32_t cells_per_texel = 0;
    std::string margin_parameter; // "caustics_depth"
    double margin_scale = 0, margin_add = 0;
    std::string window_parameter; // "caustics_window"
    uint32_t texels = 0;          // the target's side (the variant's caustics_map_texels)
    std::string format;           // "R32_SFLOAT"
    std::string channel;          // "r"
    double clear = 0;
    std::string blend; // "additive"
    // Points: this parameter must hold the grid cell's share of a texel (PassGrid::values);
    // "" for triangles.
    std::string photon_share_parameter;
};

// A variant's reference to a pass (the manifest entry).
struct PassReference {
    std::string method;                                    // "area_ratio", "photon_splat"
    std::string wave_model;                                // "gerstner", "sum_of_sines"
    std::string directory;                                 // relative to the build directory
    std::map<std::string, std::vector<std::string>> files; // by kind, as a variant's
    PassDraw draw;
    // Values the variant's scene fixed for parameters the pass reads (the water variant folded
    // them); ShaderBuild::pass() makes them the pass's values.
    std::map<std::string, std::vector<double>> values;
};

struct PassGrid {
    std::vector<float> vertices; // the attribute, two floats per vertex, less `centre`
    // The frame the vertices are in (host_values.h): the window corner's frame_centre_of, so
    // the grid is exact however far the window is from the world origin. Pack the pass with
    // UniformWriter::set_frame({centre, the floating origin}).
    FrameCentre centre;
    std::vector<uint32_t> indices; // a triangle list, or one index per point
    bool points = false;
    uint32_t texels = 0; // the target's side
    // Parameters the grid decides (photon_share_parameter: 1 / cells_per_texel^2).
    std::map<std::string, std::vector<float>> values;
};

// The most vertices a pass grid may have (pass_grid() refuses more, draw_pass() too): beyond
// it the grid is not a caustics pass's (256 x 256 texels, 8 cells each way and a margin make
// 4.2M points).
constexpr size_t kMaxPassGridVertices = size_t(1) << 26;

// The grid of `draw` for the window (x0, z0, size) and the margin parameter's value: cells of
// a texel / cells_per_texel, the margin rounded up to whole texels; triangles with vertices on
// the cell corners, rows from large z to small; points at the cell centres (so that under flat
// water each texel catches cells_per_texel^2 of them). nullopt and `error` for a window
// without a positive size, a negative margin, an unknown primitive or a grid beyond 2^26
// vertices.
std::optional<PassGrid> pass_grid(const PassDraw& draw, std::span<const double> window,
                                  double margin_value, std::string* error);

} // namespace watergen
