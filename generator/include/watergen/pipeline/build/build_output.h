// `watergen build` as a library call: plan the scenes, build every needed variant in
// parallel (cached), and write the variants plus manifest.json into the output directory as
// one atomic step (a staging directory beside it, then a rename), so a failed, invalid or
// killed build leaves the previous output exactly as it was.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/pipeline/manifest/manifest.h"
#include "watergen/pipeline/shards/sharded_build.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/scene_pruning.h"

namespace watergen {

// The name of the single "scene" of a build without scenes: every variant, not folded.
constexpr const char* kUnprunedScene = "unpruned";

struct BuildPlan {
    std::vector<ScenePlan> scenes; // sorted by name; empty: unpruned
    JobList jobs; // sorted by (scene, key); facts point into `scenes`; unpruned: compact
    std::vector<ManifestScene> manifest_scenes;
};

// Plans every scene against the material; nullopt with one error on bad input (unknown
// parameters, duplicate scene names, a scene that needs nothing). The plan must not be
// copied after this (jobs point at its scenes' facts).
// In the specialized and branching modes the jobs are the shaders of each scene's variants
// (shaders_for(), water_shader.h), each listing the variants it serves. With `shard`, only the
// jobs whose key is in it (the scenes stay whole: the manifest counts them).
std::optional<BuildPlan> plan_build(const Material& material, const std::vector<SceneFacts>& scenes,
                                    Diagnostics& ds, BuildMode mode = BuildMode::Permutations,
                                    const Shard& shard = {});

// The shader a build for the scene ships: the material's composition of `v`, folded under the
// scene's facts, built in both languages (as one variant, not through the jobs and the cache).
VariantBuild build_for_scene(const Material& material, const ScenePlan& plan, const Variant& v);

struct BuildSummary {
    size_t variants = 0; // reached (scene, variant) pairs
    size_t shaders = 0;  // jobs: one per variant, or (specialized, branching) per shared shader
    size_t built = 0;    // compiled now
    size_t cached = 0;   // copied from the cache
    size_t shared = 0;   // same files as a variant of another scene, built once for both
    size_t same = 0;     // same shader as another variant of the scene (not built again)
    size_t failed = 0;
    StageCounts stages;        // of the built: toolchain runs, and stages another's run served
    size_t cache_rejected = 0; // cache entries that failed verification: evicted and rebuilt
    size_t passes = 0;         // companion passes written (passes/<pass>/)
    size_t passes_cached = 0;  // of them, copied from the cache
    size_t frozen = 0;         // --freeze: modules frozen per variant and language path
    size_t frozen_cached = 0;  // of them, copied from the cache
    size_t files = 0;          // written (or, up to date, verified)
    bool up_to_date = false;   // the record matched and the output was intact: nothing done
    double seconds = 0;
    bool bad_input =
        false; // the error is in the description files or the output path (exit 2), not in a shader
    Diagnostics diagnostics;
    bool ok() const { return !bad_input && failed == 0 && !has_errors(diagnostics); }
};

struct BuildRequest {
    Material material;
    std::vector<SceneFacts> scenes; // none: the material's whole space, unpruned
    std::filesystem::path out;
    BuildOptions options;
    BuildMode mode = BuildMode::Permutations;
    // Specialized mode: also write each variant's SPIR-V with its selectors frozen offline
    // (freeze_specialization(), spirv_tools_stage.h) as <shader>/<lang>/frozen/<variant>.frag.spv.
    bool freeze = false;
    // What the material and scene files hash to (build_inputs_hash(), build_record.h). With a
    // cache, a build whose record matches and whose output is intact does nothing, and a
    // successful build stores its record. Empty: no record.
    std::string inputs_hash = "";
    // Only the jobs of this shard (permutations mode), and shard.json beside the manifest.
    Shard shard = {};
    // Jobs a permutations build runs at once (run_build_jobs over a range): memory holds one
    // batch's results, a few KB a job; a stage two batches share is compiled once per batch.
    // Output bytes do not depend on it.
    size_t batch_jobs = 4096;
};

// The summary of a no-op build when the request's record (inputs_hash, shard, out, cache)
// matches and every recorded output file is intact; nullopt when a build must run. Needs no
// material: a caller may ask before loading one (loading the full space's material alone costs
// 0.1 s).
std::optional<BuildSummary> build_up_to_date(const BuildRequest& request);
// build_up_to_date, then (when a build must run) build_material_now.
BuildSummary build_material(const BuildRequest& request);
// The build without the no-op check, for a caller that has just made it (the CLI checks before
// it loads the material): re-reading and re-hashing every recorded output would be done twice.
BuildSummary build_material_now(const BuildRequest& request);

// Puts `files` in place of the output directory `out` as one atomic step, if `out` may be
// replaced (check_output_target(), with `recorded`: what the build record says watergen wrote
// there); the error otherwise, and `out` untouched.
std::optional<std::string> publish_output(const std::filesystem::path& out, const FileMap& files,
                                          const std::vector<std::string>& recorded = {});

} // namespace watergen
