// What an engine does with a build, through the runtime library only, for the runtime_engine_*
// render tests: a variant drawn on the library's HeadlessDevice (files, UniformWriter,
// VariantPipeline), and a variant's caustics pass drawn there (create_pass_pipeline, pass_grid,
// HeadlessDevice::draw_pass) into the texture the variant samples.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/headless/headless_device.h"
#include "watergen/runtime/shader_build.h"
#include "watergen/water/presets.h"

namespace watergen::test {

// One device per test binary (lavapipe); FAILs without one.
HeadlessDevice& engine_gpu();

struct EngineDraw {
    std::vector<float> rgba;
    std::vector<uint8_t> uniforms;
};

// The variant's files of one language path, `values` set where the variant has the parameter
// (a scene feeds every node; a variant reads fewer), packed, drawn size x size with `textures`;
// the pipeline in the build's shared `layout` when given.
EngineDraw engine_draw(const ShaderBuild& b, const BuildVariant& v, const std::string& lang,
                       const std::map<std::string, std::vector<double>>& values,
                       const std::map<std::string, TextureData>& textures, uint32_t size,
                       VkPipelineCache cache = VK_NULL_HANDLE,
                       const BindingLayout* layout = nullptr);

struct EnginePass {
    TextureData texture;
    std::vector<double> intensity; // the texture's r, row-major
    std::vector<double> draw_ms;   // wall time of each draw_pass() call after the first
};

// The pass of one language path with `values` (the pass's parameters only; the grid's own
// values added), drawn 1 + `timed` times through HeadlessDevice::draw_pass; REQUIREs success.
EnginePass engine_pass(const ShaderBuild& b, const BuildPass& pass, const std::string& lang,
                       const std::map<std::string, std::vector<double>>& values,
                       uint32_t timed = 0);

// Largest |a - b| over equal-sized arrays (REQUIREs finite values and equal sizes).
double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b);
double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b);

} // namespace watergen::test
