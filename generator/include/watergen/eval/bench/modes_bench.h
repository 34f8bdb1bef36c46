// The build modes side by side (watergen bench modes): for a material, per mode, what building
// costs (generate + compile, single thread), how much SPIR-V it makes, and what a variant costs
// on lavapipe (pipeline creation, first draw with the LLVM JIT, steady draw), with each mode's
// image of a variant held against the permutation's.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "watergen/eval/measure/gpu_target.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/plan/material.h"
#include "watergen/runner/vulkan_runner.h"

namespace watergen {

struct ModesBenchOptions {
    uint32_t size = 256; // image width and height
    size_t variants = 6; // variants rendered, spread over the material's (0: every one)
    unsigned rounds = 3; // renders per variant and mode, the modes interleaved
    uint32_t draws = 5;  // timed draws per render
    // AMD families whose compiler (ACO, RADV's null device) also builds every rendered
    // variant's pipeline in every mode: register pressure and occupancy per mode.
    std::vector<GpuTarget> gpu_targets;
};

// One mode's pipelines on one AMD family, over the rendered variants (GLSL path, fragment stage,
// each variant's pipeline as that mode makes it: its selectors as specialization constants, or
// as uniforms of the branching shader): medians, and the worst.
struct ModeTargetCost {
    double instructions = 0, per_pixel = 0, vgprs = 0, sgprs = 0, waves_per_simd = 0;
    double code_bytes = 0, spills = 0;
    double vgprs_max = 0, waves_min = 0; // the worst variant
};

// One mode's numbers for one rendered variant: medians over the rounds.
struct ModeVariantTimes {
    std::string key;
    double pipeline_ms = 0, first_draw_ms = 0, steady_ms = 0;
    double max_abs = 0; // against the permutation's image, GLSL and HLSL paths
};

struct ModeRow {
    std::string mode; // permutations, permutations A/A (the same again: the noise), specialized,
                      // specialized frozen, branching
    size_t shaders = 0;
    double generate_compile_ms = 0;  // every shader of the material, one thread
    double spirv_bytes = 0;          // fragment SPIR-V the mode ships (GLSL path, optimised)
    double spirv_bytes_per_draw = 0; // the module a variant's pipeline is made from
    std::vector<ModeVariantTimes> variants;
    double pipeline_ms = 0, first_draw_ms = 0, steady_ms = 0, max_abs = 0; // over the variants
    std::map<std::string, ModeTargetCost> targets;                         // by target name
};

struct ModesBenchResult {
    std::string material;
    size_t material_variants = 0;
    std::vector<ModeRow> rows;
    std::vector<std::string> targets; // the AMD families measured, in the order asked
    std::string device;
    std::string csv, json;   // modes.csv, modes.json
    std::string targets_csv; // modes_targets.csv: per mode and AMD family (with gpu_targets)
    std::string error;
    bool ok() const { return error.empty(); }
    // The first mode whose image differs from the permutation's by more than `tolerance`.
    const ModeRow* beyond(double tolerance) const;
};

// Cost: every variant built once (permutations), the shared shaders, every variant frozen, then
// variants x rounds x 5 renders (each a pipeline JIT-compiled by lavapipe, 0.1-2 s).
ModesBenchResult bench_modes(VulkanRunner& runner, const Material& material,
                             const ModesBenchOptions& options);

} // namespace watergen
