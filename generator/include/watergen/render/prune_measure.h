// What scene pruning saves, measured: a variant built as composed (unpruned) and folded
// under a scene's facts (pruned), both rendered on the Vulkan runner over the synthetic scene
// made to obey those facts, with SPIR-V sizes, GPU times and the image difference.
#pragma once

#include <string>

#include "watergen/plan/material.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/render/synthetic_scene.h"
#include "watergen/render/variant_render.h"

namespace watergen {

// The synthetic scene changed where it contradicts the scene's facts, so that a shader folded
// under them must draw what the unpruned one draws: fixed parameters become its uniforms, the
// eye moves into the camera height range, the sun into the elevation range, and every water
// texel's scene point slides along its view ray into the depth range. `notes` says what moved.
SyntheticScene conform_scene(const SyntheticScene& base, const ScenePlan& plan,
                             const Material& material, std::string* notes = nullptr);

struct PruneMeasurement {
    std::string scene, key;
    std::string same_as_unpruned;                // "" when the fold changed the shader
    size_t live_before = 0, live_after = 0;      // live IR nodes
    size_t spirv_unpruned = 0, spirv_pruned = 0; // fragment instructions as compiled (GLSL path)
    size_t spirv_opt_unpruned = 0, spirv_opt_pruned = 0; // after spirv-opt -O (GLSL path)
    double gpu_ms_unpruned = 0, gpu_ms_pruned = 0;       // fastest GPU time per draw, GLSL path
    double gpu_ms_unpruned_hlsl = 0, gpu_ms_pruned_hlsl = 0;
    double max_abs_glsl = 0, max_abs_hlsl = 0, max_abs_cpu = 0; // pruned vs unpruned images
    std::string error;
    bool ok() const { return error.empty(); }
};

// Builds both shaders of `variant` (which `plan` must reach), renders both through both
// languages and the CPU evaluator on `scene` (already conformed) `rounds` times, alternating,
// and compares the images of the first round. GPU times are the fastest of all timed draws.
// Cost: two variant builds (~50 ms) and 4 x rounds pipelines (lavapipe JIT, 0.1-0.5 s each).
PruneMeasurement measure_pruning(VulkanRunner& runner, const Material& material,
                                 const ScenePlan& plan, const Variant& variant,
                                 const SyntheticScene& scene, const RenderSettings& settings,
                                 unsigned rounds = 1);

} // namespace watergen
