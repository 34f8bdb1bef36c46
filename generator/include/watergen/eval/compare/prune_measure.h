// What scene pruning saves, measured: a variant built as composed (unpruned) and folded
// under a scene's facts (pruned), both rendered on the Vulkan runner over the synthetic scene
// made to obey those facts, with SPIR-V sizes, GPU times and the image difference.
#pragma once

#include <optional>
#include <string>

#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/scene/scene_conform.h"
#include "watergen/plan/material.h"
#include "watergen/plan/scene_pruning.h"

namespace watergen {

// A variant built twice: as composed (unpruned) and folded under a scene's facts (pruned).
struct PrunePair {
    VariantBuild unpruned, pruned;
    size_t live_before = 0, live_after = 0; // live IR nodes
    std::string error;                      // "" when both built
    bool ok() const { return error.empty(); }
};

// Cost: two variant builds (~50 ms); thread-safe.
PrunePair build_prune_pair(const Material& material, const ScenePlan& plan, const Variant& v);

struct PruneMeasurement {
    std::string scene, key;
    size_t live_before = 0, live_after = 0;      // live IR nodes
    size_t spirv_unpruned = 0, spirv_pruned = 0; // fragment instructions as compiled (GLSL path)
    size_t spirv_opt_unpruned = 0, spirv_opt_pruned = 0;        // after spirv-opt -O (GLSL path)
    double max_abs_glsl = 0, max_abs_hlsl = 0, max_abs_cpu = 0; // pruned vs unpruned images
    std::string error;
    bool ok() const { return error.empty(); }
};

// The sizes of a built pair (the image differences left at 0).
PruneMeasurement pair_sizes(const ScenePlan& plan, const Variant& v, const PrunePair& pair);

// The largest difference of two images of one pair, or an error when they cannot be compared
// (sizes, or non-finite pixels in one and not the other).
std::optional<double> pruned_difference(const ImageRGBA32F& pruned, const ImageRGBA32F& unpruned,
                                        std::string* error);

// Builds both shaders of `variant` (which `plan` must reach), renders both through both
// languages and the CPU evaluator in float on `scene` (already conformed), and compares the
// images. Cost: two variant builds, four pipelines (lavapipe JIT, 0.1-0.5 s each), two CPU
// evaluations.
PruneMeasurement measure_pruning(VulkanRunner& runner, const Material& material,
                                 const ScenePlan& plan, const Variant& variant,
                                 const SyntheticScene& scene, const RenderSettings& settings);

} // namespace watergen
