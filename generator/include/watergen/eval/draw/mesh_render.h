// A mesh geometry's variant (geometry=mesh or tessellated) drawn on the Vulkan runner: the
// runtime library's clipmap grid (watergen/runtime/water_grid.h) around the scene's eye, seen
// by the scene's camera, through both languages. The water is drawn over the lit scene, as an
// engine draws it: a pixel no triangle covers shows the scene colour.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/runtime/water_grid.h"

namespace watergen {

struct MeshRenderSettings {
    uint32_t width = 256, height = 256;
    WaterGridDesc grid{};
    uint32_t timed_draws = 0;
    bool cull_back_faces = false; // RenderJob::cull_back_faces: see which way triangles wind
    // Parameter values over the scene's and the camera's (tess_scale, tess_max, ...).
    std::map<std::string, std::vector<double>> overrides{};
};

// The grid's vertices and indices as the runner draws them (attributes grid_xz, grid_lod).
MeshData grid_mesh(const WaterGrid& grid);

// The grid of `desc` around the eye of the scene's camera: patches for a tessellated variant.
// Throws std::invalid_argument for a description out of range (check water_grid_error first).
WaterGrid scene_grid(const SyntheticScene& scene, const WaterGridDesc& desc, bool tessellated,
                     uint32_t width, uint32_t height);
// Its triangles, or patches.
uint64_t grid_primitives(const WaterGrid& grid);

// Per pixel (row-major, row 0 at the top), the morph weight of the grid (`desc`, built as
// `grid`) where the pixel's ray
// meets the mean water level (y = water_level): t in [0, 1] of the clipmap level holding that
// point (water_grid.h: 0 still, 1 on the coarser level's grid), or -1 where the ray misses the
// water or the grid. Waves move the surface off the mean level, so a pixel near a band's edge
// may be classed with its neighbour; the split of an image's error by band is what it is for.
std::vector<double> morph_weights(const SyntheticScene& scene, const WaterGridDesc& desc,
                                  const WaterGrid& grid, uint32_t width, uint32_t height);

// Whether a built language path draws a mesh (its vertex stage takes the grid's attributes).
bool draws_mesh(const LanguageBuild& lang);

// The parameter values of a mesh draw: scene.uniforms (eye, time, level, sun), the scene
// camera at width x height (mesh_camera_*, mesh_projection) and the grid's morph range.
std::map<std::string, std::vector<double>>
mesh_values(const SyntheticScene& scene, const WaterGrid& grid, uint32_t width, uint32_t height);

// The runner job of one language of a mesh variant drawing `mesh` (triangles, or patches for
// a tessellated one) with the scene's textures and the block packed from `values`, over the
// scene's colour (RenderJob::background).
RenderJob mesh_render_job(const LanguageBuild& lang, const SyntheticScene& scene,
                          const MeshData& mesh,
                          const std::map<std::string, std::vector<double>>& values, uint32_t width,
                          uint32_t height, uint32_t timed_draws);

struct MeshRender {
    std::array<RenderResult, 2> gpu;       // GLSL path, HLSL path, over the scene's colour
    std::array<ImageRGBA32F, 2> gpu_image; // the same as images
    ImageErrorStats glsl_vs_hlsl;
    uint64_t vertices = 0, primitives = 0; // the grid's vertices; triangles or patches
    uint64_t covered = 0;                  // pixels a fragment wrote (GLSL path)
    std::vector<std::string> validation_messages;
    std::string error;
    bool ok() const { return error.empty(); }
};

// Both languages of a mesh variant drawn over its grid; an error for a screen-pass variant, a
// grid description out of range (water_grid_error) or a scene of another size.
MeshRender render_mesh_variant(VulkanRunner& runner, const VariantBuild& build,
                               const SyntheticScene& scene, const MeshRenderSettings& settings);

// The screen pass of the same choices (geometry=screen_pass), whose surface search finds
// where each pixel's ray meets the surface to convergence: the exact surface a mesh
// approximates, shaded by the same nodes.
Variant screen_pass_of(const Variant& mesh_variant);

// That exact surface's fragment as a material ships its shaders: the screen pass of the mesh
// variant's choices, search converged, composed by `material` and, with `plan`, folded under
// the scene's facts (as build_for_scene folds). What a CPU reference of a mesh variant
// evaluates: its own fragment needs the rasterised grid's inputs.
Graph exact_surface_fragment(const Material& material, const ScenePlan* plan,
                             const Variant& mesh_variant);

// A mesh variant drawn (render_mesh_variant with settings.grid) and the screen pass of the same
// choices evaluated on the CPU in double (and in float when settings.cpu_float) over the same
// scene: glsl_vs_cpu_double is the mesh's error against the exact surface. No float bound or
// agreement (a different model, not rounding).
struct VariantRender;
struct RenderSettings;
VariantRender render_mesh_against_surface(VulkanRunner& runner, const VariantBuild& build,
                                          const SyntheticScene& scene,
                                          const RenderSettings& settings);

} // namespace watergen
