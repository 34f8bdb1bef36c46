// Builds many variants on all cores. Each job composes its variant from the material, folds
// it under its scene's facts, emits the sources and hashes them; variants of one scene whose
// folded shaders are identical are built once (the others point at it); the rest are taken
// from the cache or compiled, validated, optimised, cross-compiled and reflected. Results come
// back in job order, whatever the thread count or timing, so output is byte-identical.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "watergen/ir/binding_map.h"
#include "watergen/ir/ir_fold.h"
#include "watergen/pipeline/build_cache.h"
#include "watergen/plan/material.h"

namespace watergen {

struct BuildJob {
    std::string scene; // output directory of the scene
    Variant variant;
    const FoldFacts* facts = nullptr; // fold under these; nullptr builds the variant as composed
    std::vector<Target> targets;
    // Set in the specialized and branching modes: the job builds this shader, which draws the
    // variants of `serves` (sorted by key); `variant` is the one its selectors' defaults draw.
    std::optional<ShaderChoices> shader = std::nullopt;
    std::vector<Variant> serves = {};
};

// The job's key: its variant's, or its shader's (ShaderChoices::key).
std::string job_key(const BuildJob& job);

struct JobResult {
    std::string content_hash; // cache key of the files
    std::string shape_hash;   // of the sources without the variant key
    std::string same_as;      // key of the earlier variant of the scene with the same shader
    bool folded = false;
    FoldReport fold;
    FileMap files; // relative to the variant directory, filtered by targets (empty once a
                   // BuildOptions::sink took them)
    // The names of `files`, sorted; kept when a sink takes the bytes. One list is shared by
    // every job that writes the same names (most of a build's): a list per job was most of a
    // long build's memory.
    std::shared_ptr<const std::vector<std::string>> names;
    const std::vector<std::string>& file_names() const;
    bool cached = false;
    std::string cache_rejected; // why its cache entry failed verification (evicted, rebuilt); "" if
                                // it did not
    bool shared = false;        // same content as a job of another scene, built once for both
    Diagnostics diagnostics;
    double milliseconds = 0;
    bool ok() const { return !has_errors(diagnostics); }
};

struct BuildProgress {
    size_t done = 0, total = 0, cached = 0, failed = 0;
    std::string key; // the job that just finished
};

struct BuildOptions {
    unsigned threads = 0; // 0: every hardware thread
    BuildCache cache;     // disabled by default
    // Called after each job, one call at a time, in completion order (progress display only).
    std::function<void(const BuildProgress&)> progress;
    // Called on the worker thread, concurrently, with each job (index, result) whose files are
    // done (a built job, or one that takes another scene's files), before `progress`: a streaming
    // build writes them out and clears JobResult::files, so memory holds the jobs in flight only.
    std::function<void(size_t, JobResult&)> sink;
    // Where every shader's resources are bound (ir/binding_map.h); null: the watergen profile.
    const BindingMap* bindings = nullptr;
};

unsigned hardware_threads();

// The most worker threads any --jobs runs: kJobsPerHardwareThread per hardware thread (a few per
// core still help when tasks wait on child processes; past that they only contend).
inline constexpr unsigned kJobsPerHardwareThread = 4;
unsigned max_jobs();

// Runs task(i) for every i in [0, n) on `threads` workers (0: all cores; 1: the calling thread),
// never more than n nor max_jobs().
void parallel_for(size_t n, unsigned threads, const std::function<void(size_t)>& task);

struct StageCounts; // stage_memo.h

// Jobs must be sorted by (scene, job_key) for `same_as` to name the first of equal shaders.
// A stage several jobs compile (the vertex shader every variant has; a fragment two scenes
// fold alike) is compiled once (StageMemo); how many were compiled and reused goes to
// `stage_counts`. The HLSL path is not cross-compiled: a build ships SPIRV-Cross text of the
// GLSL path only.
std::vector<JobResult> run_build_jobs(const Material& material, const std::vector<BuildJob>& jobs,
                                      const BuildOptions& options,
                                      StageCounts* stage_counts = nullptr);

// The files of `all` a target list keeps (variant.json and a pass's pass.json always; see
// docs/user-guide.md "Build output").
FileMap filter_targets(const FileMap& all, const std::vector<Target>& targets);

} // namespace watergen
