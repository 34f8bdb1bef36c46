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
#include <string_view>
#include <unordered_map>
#include <vector>

#include "watergen/ir/emit/binding_map.h"
#include "watergen/ir/fold/ir_fold.h"
#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/jobs/job_list.h"
#include "watergen/plan/material.h"

namespace watergen {

struct JobResult {
    std::string content_hash; // cache key of the files
    std::string shape_hash;   // of the sources without the variant key
    std::string same_as;      // key of the earlier variant of the scene with the same shader
    size_t same_as_job = 0;   // its job (when same_as is set), whose files `names` then lists
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
    // The job whose files job `i` (this result's) has: itself, or the one of same_as.
    size_t files_of(size_t i) const { return same_as.empty() ? i : same_as_job; }
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
    // A job of an earlier batch (run_build_jobs over a range) whose files a later job of another
    // scene takes: its files (`names`) read back from where the sink put them; nullopt if they
    // cannot be (the later job then builds its own). Unset: the later job builds its own.
    std::function<std::optional<FileMap>(size_t job, const std::vector<std::string>& names)>
        read_back;
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

class NameLists;

// What the batches of one build's jobs pass on to the next (run_build_jobs over a range of
// jobs): per shape of the current scene its first job, per content the job that built it (for
// the scenes still to come), and the progress so far. It grows by the distinct shaders, about
// 60 bytes each, not by their results.
struct BuildLedger {
    BuildLedger();
    ~BuildLedger();
    BuildLedger(const BuildLedger&) = delete;
    BuildLedger& operator=(const BuildLedger&) = delete;

    struct Hash128 {
        uint64_t high = 0, low = 0;
        bool operator==(const Hash128&) const = default;
    };
    struct HashOf {
        size_t operator()(const Hash128& h) const { return static_cast<size_t>(h.low); }
    };
    // A content or shape hash's text as the ledger keys it: 16 bytes (XXH3-128), not the text.
    static Hash128 hash_of(std::string_view text);
    struct Built {
        size_t job = 0;
        std::shared_ptr<const std::vector<std::string>> names; // once its files exist
    };
    std::string scene;                                // of the shapes in `first`
    std::unordered_map<Hash128, Built, HashOf> first; // shape -> first job of the scene
    std::unordered_map<Hash128, Built, HashOf> built; // content -> the job that built it
    std::unique_ptr<NameLists> name_lists;
    BuildProgress progress;
};

// Jobs must be sorted by (scene, job_key) for `same_as` to name the first of equal shaders.
// A stage several jobs compile (the vertex shader every variant has; a fragment two scenes
// fold alike) is compiled once (StageMemo); how many were compiled and reused goes to
// `stage_counts`. The HLSL path is not cross-compiled: a build ships SPIRV-Cross text of the
// GLSL path only.
std::vector<JobResult> run_build_jobs(const Material& material, const std::vector<BuildJob>& jobs,
                                      const BuildOptions& options,
                                      StageCounts* stage_counts = nullptr);
// The jobs `batch` of `list`, its jobs [begin, begin + batch.size()) (results[k] is job
// begin + k), after the earlier ranges of the same build (`ledger`): a job with the shape or
// content of an earlier range's job points at it or takes its files (BuildOptions::read_back),
// as one run over all the jobs would. Progress counts every job of `list`; stage counts are
// added to `stage_counts`. A build runs its jobs a batch at a time so that memory holds one
// batch's jobs and results.
std::vector<JobResult> run_build_jobs(const Material& material, const JobList& list, size_t begin,
                                      const std::vector<BuildJob>& batch,
                                      const BuildOptions& options, BuildLedger& ledger,
                                      StageCounts* stage_counts = nullptr);

// The files of `all` a target list keeps (variant.json and a pass's pass.json always; see
// docs/user-guide.md "Build output").
FileMap filter_targets(const FileMap& all, const std::vector<Target>& targets);

} // namespace watergen
