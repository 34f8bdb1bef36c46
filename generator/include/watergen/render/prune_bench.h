// Pruning benchmark as a library call (`watergen bench prune` prints it): per scene, each
// distinct folded shader against the same variant unpruned, rendered on the Vulkan runner
// over the synthetic scene conformed to the scene's facts (measure_pruning): SPIR-V
// instruction counts, GPU time per draw, and how far the images differ.
#pragma once

#include <string>
#include <vector>

#include "watergen/render/prune_measure.h"

namespace watergen {

struct PruneBenchOptions {
    uint32_t size = 256;  // image width and height
    uint32_t draws = 21;  // timed draws per render and language
    unsigned rounds = 3;  // renders per shader, alternating pruned and unpruned
    size_t per_scene = 0; // at most this many distinct shaders per scene; 0: all
};

struct PruneBenchRow {
    std::string key;       // the variant
    std::string short_key; // the choices of the axes the material varies, without axis names
    PruneMeasurement measurement;
    double max_diff = 0; // over the GLSL, HLSL and CPU images
};

struct PruneBenchScene {
    std::string name;
    std::string notes;               // what conform_scene moved
    std::vector<PruneBenchRow> rows; // one per distinct folded shader, in plan order
    bool complete = false; // false when a measurement failed (the rows before it are kept)
    // Medians over the rows of pruned / unpruned; the largest image difference.
    double ir = 0, spirv = 0, spirv_opt = 0, gpu_glsl = 0, gpu_hlsl = 0, worst = 0;
};

struct PruneBenchResult {
    std::vector<PruneBenchScene> scenes; // in plan order; the last one incomplete on error
    std::string error;                   // "scene: key: why" of the failed measurement
    bool ok() const { return error.empty(); }
    bool within(double tolerance) const; // every image difference is at most `tolerance`
};

// Measures every scene of `plans` (planned against `material`). Cost per distinct shader:
// see measure_pruning.
PruneBenchResult bench_prune(VulkanRunner& runner, const Material& material,
                             const std::vector<ScenePlan>& plans, const PruneBenchOptions& options);

} // namespace watergen
