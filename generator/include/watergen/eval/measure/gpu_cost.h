// A variant's cost on AMD GPU families: ACO's statistics of its pipeline (aco_worker.h) per
// stage, and for the fragment stage a per-pixel instruction estimate that weights each loop
// body by its trip count (aco_loops.h), the loops matched to the IR's in the order the emitter
// writes them (emitted_loops()).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/measure/aco_worker.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/pipeline/variant/variant_build.h"

namespace watergen {

struct StageGpuCost {
    std::string stage; // "vertex", "fragment"
    double instructions = 0, vgprs = 0, sgprs = 0, spilled_vgprs = 0, spilled_sgprs = 0;
    double scratch_bytes = 0, code_bytes = 0, waves_per_simd = 0;
    double latency = 0, inverse_throughput = 0; // ACO's scheduler model, in cycles
    // Instructions one invocation executes if every loop runs its trip count (an upper bound
    // for a loop whose count comes from data or that may exit early); nullopt when the
    // driver's loops cannot be matched to the IR's (per_pixel_note says why).
    std::optional<double> per_pixel;
    std::string per_pixel_note;
    uint32_t loops = 0; // loops the driver kept
};

struct PipelineGpuCost {
    std::string name;
    std::vector<StageGpuCost> stages; // vertex, fragment
    std::string error;                // the driver refused the pipeline
    bool unsupported = false;         // not compiled: the family lacks a feature (aco_device.h)
    bool ok() const { return error.empty(); }
    const StageGpuCost* stage(const std::string& name) const;
    // The fragment stage's per-pixel estimate, else its static count: what the Pareto uses.
    double fragment_cost() const;
};

// The ACO job of one language path of a built variant (its optimised SPIR-V, as render draws
// it) with the given specialization constants.
AcoPipelineSource aco_source(const LanguageBuild& lang, const std::string& name,
                             const std::map<uint32_t, float>& specialization = {});

// The statistics of a pipeline as costs; `fragment_loops` are the IR's loops of its fragment
// stage (emitted_loops of the shader's graph).
PipelineGpuCost gpu_cost(const AcoPipelineStatistics& stats,
                         const std::vector<EmittedLoop>& fragment_loops);

// The columns every cost table and CSV prints per target and stage, in this order.
struct GpuCostColumn {
    const char* name; // "instructions", "vgprs", ...
    double StageGpuCost::*value;
};
const std::vector<GpuCostColumn>& gpu_cost_columns();

// The null device's cost of each built variant's language paths on each target (not
// lavapipe): per target, per variant, the GLSL path then the HLSL path. A target whose
// worker failed has its run's error and no costs. `names` label the variants; `unroll` is
// the EmitOptions::unroll they were built with.
struct TargetCosts {
    AcoTargetRun run;                   // device, driver, error
    std::vector<PipelineGpuCost> costs; // 2 per variant: GLSL, HLSL
};
std::vector<TargetCosts> variant_gpu_costs(const std::vector<GpuTarget>& targets,
                                           const std::vector<const VariantBuild*>& builds,
                                           const std::vector<std::string>& names,
                                           const std::filesystem::path& scratch,
                                           LoopUnroll unroll = LoopUnroll::AsHinted,
                                           const std::filesystem::path& worker = own_executable());

// What compare, pick and the benches trade: per target, each build's GLSL fragment cost
// (PipelineGpuCost::fragment_cost), nullopt where the family lacks a feature the shader needs
// (PipelineGpuCost::unsupported). `error` is the first failure: a worker that failed
// (`no_device` when its null device is missing) or a pipeline the driver refused.
struct GlslFragmentCosts {
    std::vector<std::vector<std::optional<double>>> costs; // [target][build]
    std::string error;
    bool no_device = false;
    bool ok() const { return error.empty(); }
};
GlslFragmentCosts glsl_fragment_costs(const std::vector<GpuTarget>& targets,
                                      const std::vector<VariantBuild>& builds,
                                      const std::vector<std::string>& names,
                                      LoopUnroll unroll = LoopUnroll::AsHinted);

} // namespace watergen
