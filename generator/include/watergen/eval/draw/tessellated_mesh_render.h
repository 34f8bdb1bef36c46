// The tessellated mesh path drawn on the Vulkan runner: quad patches of grid points through
// both languages' four stages (pipeline/tessellated_mesh_build.h), with the synthetic scene's
// camera, GLSL image against HLSL image. Needs the device's tessellationShader feature.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "watergen/eval/draw/mesh_render.h"
#include "watergen/pipeline/tessellated_mesh_build.h"

namespace watergen {

// n x n grid points spanning [x0, x1] x [z0, z1] (attribute grid_xz), (n - 1)^2 patches of 4
// control points: corners (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1), the order the patch
// skeletons take as (u, v) = (0, 0), (1, 0), (0, 1), (1, 1); rows from z1 down to z0, back to
// front for a camera looking along +z, as make_grid's (the runner has no depth buffer).
MeshData make_patches(uint32_t n, double x0, double x1, double z0, double z1);

// The runner job of one language drawing `patches` at width x height, the shared block packed
// from `values` over the defaults.
RenderJob tessellated_mesh_job(const TessellatedLanguageBuild& lang, const MeshData& patches,
                               uint32_t width, uint32_t height,
                               const std::map<std::string, std::vector<double>>& values,
                               uint32_t timed_draws);

// Both languages drawn as render_mesh draws the mesh path (settings.grid: grid points per side,
// so settings.grid - 1 patches per side); `overrides` (tess_scale, tess_max, ...) over the
// scene's values.
MeshRender
render_tessellated_mesh(VulkanRunner& runner, const TessellatedMeshBuild& build,
                        const SyntheticScene& scene, const MeshRenderSettings& settings,
                        const std::map<std::string, std::vector<double>>& overrides = {});

} // namespace watergen
