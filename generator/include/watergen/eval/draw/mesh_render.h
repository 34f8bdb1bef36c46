// The mesh path end to end: build both languages of a MeshShader, draw it over an N x N grid
// on the Vulkan runner with the synthetic scene's camera, and compare the two images.
#pragma once

#include <array>
#include <map>
#include <string>

#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/pipeline/variant_build.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/water/mesh_shader.h"

namespace watergen {

struct MeshBuild {
    MeshShader shader;
    std::array<LanguageBuild, 2> languages; // GLSL, HLSL
    Diagnostics diagnostics;
    bool ok() const { return !has_errors(diagnostics); }
};

// The runner job of one language of a two-stage build drawing `mesh` at width x height, its
// parameters packed from `values` over their defaults. Only the vertex stage may read
// parameters (the pipeline has the one parameter block).
RenderJob mesh_job(const LanguageBuild& lang, const MeshData& mesh, uint32_t width, uint32_t height,
                   const std::map<std::string, std::vector<double>>& values, uint32_t timed_draws);

// The runner job drawing `mesh` with `vertex` and `fragment`, the parameter block packed from
// `values` over the defaults of the stage interface `block` declares it in.
RenderJob geometry_job(const StageBuild& vertex, const StageBuild& fragment,
                       const ShaderInterface& block, const MeshData& mesh, uint32_t width,
                       uint32_t height, const std::map<std::string, std::vector<double>>& values,
                       uint32_t timed_draws);

// build_two_stages of build_mesh_shader(wave_model).
MeshBuild build_mesh(const std::string& wave_model);

// n x n vertices with attribute grid_xz spanning [x0, x1] x [z0, z1], two triangles per cell,
// rows ordered from z1 down to z0: back to front for a camera looking along +z (the runner has
// no depth buffer).
MeshData make_grid(uint32_t n, double x0, double x1, double z0, double z1);

struct MeshRenderSettings {
    uint32_t width = 128, height = 128;
    uint32_t grid = 64;                         // vertices per side
    double x0 = -14, x1 = 14, z0 = -4, z1 = 30; // grid extent, m
    uint32_t timed_draws = 0;
    bool cull_back_faces = false; // RenderJob::cull_back_faces: see which way triangles wind
};

struct MeshRender {
    std::array<RenderResult, 2> gpu; // GLSL path, HLSL path
    std::array<ImageRGBA32F, 2> gpu_image;
    ImageErrorStats glsl_vs_hlsl;
    std::vector<std::string> validation_messages;
    std::string error;
    bool ok() const { return error.empty(); }
};

// The parameter values of a mesh draw: scene.uniforms (eye, time, level) and the synthetic
// scene's camera at settings' size (mesh_camera_*, mesh_projection, eye_position).
std::map<std::string, std::vector<double>> mesh_values(const SyntheticScene& scene,
                                                       const MeshRenderSettings& settings);

// Camera and sun of the synthetic scene at settings' size; scene.uniforms (eye, time, level)
// override parameter defaults.
// Draws the GLSL path's job (jobs[0]) and the HLSL path's, and compares the two images.
MeshRender render_language_pair(VulkanRunner& runner, const std::array<RenderJob, 2>& jobs,
                                const MeshRenderSettings& settings);

MeshRender render_mesh(VulkanRunner& runner, const MeshBuild& build, const SyntheticScene& scene,
                       const MeshRenderSettings& settings);

} // namespace watergen
