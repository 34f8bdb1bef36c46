// Renders one built variant through both language paths on the Vulkan runner and evaluates
// the same description on the CPU, then measures how far apart the images are.
#pragma once

#include <array>
#include <string>

#include "watergen/eval/image/agreement.h"
#include "watergen/eval/image/image_io.h"
#include "watergen/eval/image/image_metrics.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/runner/vulkan_runner.h"
#include "watergen/runtime/water_grid.h"

namespace watergen {

struct RenderSettings {
    uint32_t width = 256, height = 256;
    uint32_t timed_draws = 5;
    bool cpu_double = true; // also evaluate in double (costs about as much as the float pass)
    bool cpu_float = true;  // evaluate on the CPU in float at all (about 30 us per pixel)
    // With cpu_double: the float error to expect per pixel (float_error_bound) and the GPU
    // images' agreement with the CPU float image within `tolerance` plus that bound. Costs
    // kFloatBoundRuns more double evaluations.
    bool float_bound = false;
    double tolerance = kAgreementTolerance;
    // A mesh variant's grid (geometry=mesh or tessellated; the screen pass has none).
    WaterGridDesc grid{};
    // A tessellated variant's largest tessellation factor (its tess_max parameter, 1 to 64);
    // 0: the parameter's default.
    double tess_max = 0;
};

// The float error bound's model (watergen/ir/cpu/float_error.h): every operation's result moved by
// up to one binary32 ulp (2^-23 relative: GPUs round to nearest, and their exp2, sin and fused
// multiply-adds differ from correctly rounded by about an ulp), four seeded runs; two float
// evaluations of a pixel are expected within twice the largest change any run makes, plus an
// ulp of the pixel's value on either side (2^-22 of its largest component).
constexpr int kFloatBoundRuns = 4;
constexpr double kFloatBoundRelative = 0x1p-23;
constexpr double kFloatBoundFactor = 2.0;

struct VariantRender {
    std::string key;
    // A mesh variant's: the CPU images are the exact surface's (render_mesh_against_surface),
    // so glsl_vs_cpu_double is the grid's geometric error and there is no float agreement.
    bool against_surface = false;
    std::array<RenderResult, 2> gpu; // GLSL path, HLSL path (optimised SPIR-V)
    std::array<ImageRGBA32F, 2> gpu_image;
    ImageRGBA32F cpu_float, cpu_double; // CPU evaluator of the same graph and inputs
    ImageErrorStats glsl_vs_hlsl, glsl_vs_cpu_float, hlsl_vs_cpu_float, glsl_vs_cpu_double;
    // RenderSettings::float_bound: per pixel, how far apart two float evaluations may be
    // (row 0 = top); each path's agreement with the CPU float image within tolerance + that.
    std::vector<float> float_bound;
    std::array<Agreement, 2> agreement;
    double cpu_float_ms = 0;
    std::vector<std::string> validation_messages; // raised while rendering this variant
    std::string error;                            // first failure, "" when everything ran
    bool ok() const { return error.empty(); }
};

// Cost: two pipelines (each JIT-compiled by lavapipe at first draw, 0.1-0.5 s) plus
// 1 + timed_draws draws per path, plus one CPU evaluation per precision.
// A mesh variant (geometry=mesh or tessellated) is drawn over its grid (settings.grid) and
// compared with the exact surface instead (render_mesh_against_surface, mesh_render.h): the
// CPU images are the screen pass' of the same choices, and there is no float bound (the two
// differ by the grid's geometric error, not by rounding).
VariantRender render_variant(VulkanRunner& runner, const VariantBuild& build,
                             const SyntheticScene& scene, const RenderSettings& settings);

// The runner job for one language path of a built variant over `scene`: optimised SPIR-V, the
// scene's textures by binding name, uniforms packed from the scene's values over the defaults.
// A mesh variant's (draws_mesh) is drawn over settings.grid around the scene's eye, the scene
// colour under it (mesh_render_job).
RenderJob make_render_job(const LanguageBuild& lang, const SyntheticScene& scene,
                          const RenderSettings& settings);
// The same without the geometry: the stages, textures and block (the fullscreen triangle), the
// block packed from `values` (null: the scene's).
RenderJob scene_inputs_job(const LanguageBuild& lang, const SyntheticScene& scene,
                           const RenderSettings& settings,
                           const std::map<std::string, std::vector<double>>* values = nullptr);

ImageRGBA32F to_image(const EvalResult& r, uint32_t width, uint32_t height);

// The float error bound of each pixel of `graph`'s width x height image, whose double
// evaluation is `double_image`: how far apart two float evaluations may be (the model above).
// With `float_image` (the same graph in float), how far a float evaluation may be from double:
// that image's own distance from double added. Empty, with `error` set, when the evaluation
// fails.
std::vector<float> float_bound(const Graph& graph, const EvalInputs& inputs, uint32_t width,
                               uint32_t height, const EvalResult& double_image, std::string& error,
                               const EvalResult* float_image = nullptr);

} // namespace watergen
