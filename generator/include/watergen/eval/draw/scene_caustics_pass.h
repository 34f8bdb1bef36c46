// The caustics pass a variant's caustics choice reads, drawn for a scene: `watergen render` and
// `watergen compare` of caustics=area_ratio or photon_splat variants run the real chain. The
// pass of the choice's method and the variant's wave model is drawn on the runner with the
// scene's values (its uniforms over the pass's defaults: sun, time, the waves a preset sets) at
// the scene map's depth, margin and window (synthetic_scene.h), at the water node's
// caustics_map_texels; its GLSL texture then replaces the scene's CPU-made caustics_map, so the
// water pass and the CPU evaluator both sample what the GPU drew. The CPU photon reference of
// the same values measures the texture.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/draw/caustics_pass_draw.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/runner/vulkan_runner.h"

namespace watergen {

// Photons per texel side of the reference a scene's pass is measured against (64 per texel,
// as `watergen caustics` uses; the scene's own CPU map uses 9).
inline constexpr uint32_t kSceneCausticsReferencePhotons = 8;

struct SceneCausticsPass {
    CausticsMethod method = CausticsMethod::AreaRatio;
    std::string wave_model;
    uint32_t texels = 0;
    std::vector<double> window;          // caustics_window drawn: x0, z0, size (m)
    std::vector<double> intensity;       // the GLSL path's texture, row-major (row = z)
    std::vector<double> reference;       // the CPU photon reference of the same values
    RenderResult glsl;                   // its times: steady_draw_ms = median of the timed draws
    CausticsError vs_reference;          // intensity against reference
    double mean = 0, reference_mean = 0; // mean_intensity of each
    double glsl_vs_hlsl = 0;             // max abs between the two paths' textures
    Diagnostics diagnostics;             // of a pass that did not build
    std::string error;
    bool ok() const { return error.empty(); }
};

// The side of the map a built water shader reads: its caustics_map_texels parameter as the
// scene sets it (photon_splat's filter reads it), else kSceneCausticsTexels.
uint32_t scene_caustics_texels(const VariantBuild& water, const SyntheticScene& scene);

// The values a scene's pass is drawn with: the pass's defaults, the scene's uniforms over them,
// caustics_depth kSceneCausticsDepth.
std::map<std::string, std::vector<double>> scene_caustics_values(const CausticsPassBuild& build,
                                                                 const SyntheticScene& scene);

// The pass's settings for a scene: `texels`, the scene's margin, the method's cells per texel.
CausticsRenderSettings scene_caustics_settings(CausticsMethod method, uint32_t texels,
                                               uint32_t timed_draws);

// What:   draws `build` (build_caustics_pass_files) for `scene` on both paths, `timed_draws` timed
// draws
//         each, and the CPU reference of the same values.
// Cost:   two pipelines (JIT about 0.1 s each) and the draws (area ratio at 64 texels: a few ms;
//         photons: 746k points), plus 64 photons per texel on the CPU (tens of ms).
SceneCausticsPass draw_scene_caustics_pass(VulkanRunner& runner, const CausticsPassBuild& build,
                                           const SyntheticScene& scene, uint32_t texels,
                                           uint32_t timed_draws);

// The pass's texture as the scene's caustics_map.
void use_caustics_pass(SyntheticScene& scene, const SceneCausticsPass& pass);

} // namespace watergen
