// Kept loops against unrolled ones on lavapipe: the same variant emitted with every loop
// hinted [[dont_unroll]] / [loop] and with every loop hinted [[unroll]] / [unroll] (spirv-opt
// then unrolls them), timed interleaved with an A/A pair.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/ir/core/diagnostic.h"
#include "watergen/runner/vulkan_runner.h"

namespace watergen {

// One hint's figures for one variant; times are one sample per round and language path.
struct UnrollSide {
    size_t glsl_lines = 0;   // the Vulkan GLSL fragment shader
    size_t spirv_words = 0;  // optimised SPIR-V of the GLSL path's fragment stage
    size_t instructions = 0; // spirv-opt's instruction count, same module
    std::vector<double> first_draw_ms, steady_draw_ms, pipeline_ms;
    // Per AMD target: ACO's fragment stage of the GLSL path (static count, per-pixel estimate,
    // VGPRs, ...).
    std::map<std::string, StageGpuCost> targets;
};

struct UnrollBenchRow {
    std::string waves;                     // the waves choice; every other axis at its default
    UnrollSide kept, unrolled, kept_again; // kept_again: the A/A copy of `kept`
    // Per round and language path: unrolled / kept and kept_again / kept.
    std::vector<double> first_draw_ratio, first_draw_aa, steady_ratio, steady_aa;
};

struct UnrollBench {
    uint32_t size = 0, rounds = 0;
    std::vector<UnrollBenchRow> rows;
    std::vector<std::string> targets; // the AMD families measured
    std::string csv, json;            // unroll.csv, unroll.json
    Diagnostics diagnostics;          // of a build that failed
    std::string error;
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
};

// What:   for each waves choice (every other axis at its default), the fragment shader with
//         every loop kept and with every loop unrolled, rendered over the synthetic scene at
//         size x size; each round renders kept, unrolled and kept again (the A/A pair) in an
//         order that rotates from round to round, each render a new pipeline JIT-compiled at
//         its first draw (Mesa's shader cache off), then `draws` timed draws (median); and
//         the tables.
//         With `targets`, both shaders also compiled by each AMD family's ACO.
// Cost:   per round and waves choice, six pipelines (two languages x three renders).
UnrollBench run_unroll_bench(VulkanRunner& runner, uint32_t size, uint32_t rounds, uint32_t draws,
                             const std::vector<GpuTarget>& targets = {});

} // namespace watergen
