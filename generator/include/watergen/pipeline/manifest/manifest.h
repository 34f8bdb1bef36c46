// manifest.json: what a build produced, per variant its key, short hash, content hash, chosen
// nodes, folded parameters and removed terms (with the scene facts behind them), files per
// target, reflection (bindings, uniform layout) and SPIR-V instruction counts. Sorted by
// (scene, key) and free of paths, times and other run-dependent data: byte-identical for equal
// inputs, whether the material came from C++ or from a file.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/pipeline/output/json_document.h"
#include "watergen/plan/scene_pruning.h"
#include "watergen/toolchain/spirv_tools_stage.h"

namespace watergen {

// One scene of a build: a ScenePlan, or the material's whole space unpruned (plan == nullptr).
struct ManifestScene {
    std::string name;
    const ScenePlan* plan = nullptr;
    size_t variants = 0;
};

// Where the manifest finds a built job's variant.json (its reflection): (job, file name) -> the
// bytes, or nullopt. A streaming build reads it back from its staging tree.
using ReadJobFile = std::function<std::optional<std::string>(size_t job, const std::string& name)>;
// The manifest's text goes to a WriteText (json_document.h) piece by piece: the entries are made
// and written one at a time, so no build holds the whole document.

// A variant drawn with a companion pass gets "passes" (passes_entry(), caustics_pass_build.h)
// after its own files. The head records "bindings": the map every shader was emitted with
// (null: the watergen profile), with every slot spelled out.
void write_manifest(const Material& material, const std::vector<ManifestScene>& scenes,
                    const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                    const CausticsPasses& passes, const ReadJobFile& read, const WriteText& write,
                    const BindingMap* bindings = nullptr);
// The same, written as a build's batches of jobs finish (each batch's entries in job order):
// the head when made, an entry per add(), the rest at end().
class ManifestWriter {
  public:
    ManifestWriter(const Material& material, const std::vector<ManifestScene>& scenes,
                   const CausticsPasses& passes, const ReadJobFile& read, WriteText write,
                   const BindingMap* bindings = nullptr);
    // A job with its result; `built`: the job whose files it has (JobResult::files_of).
    void add(const BuildJob& job, const JobResult& r, size_t built, const BuildJob& built_job);
    void end();

  private:
    const Material& material_;
    const CausticsPasses& passes_;
    const ReadJobFile& read_;
    WriteText write_; // before doc_, which writes through it
    JsonDocumentWriter doc_;
};
// The same as one string, reading each job's files from its result (JobResult::files).
std::string manifest_json(const Material& material, const std::vector<ManifestScene>& scenes,
                          const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                          const CausticsPasses& passes = {}, const BindingMap* bindings = nullptr);

// Directory of a variant inside the output, e.g. "open_ocean/fresnel-schlick_...".
std::string variant_directory(const std::string& scene, const Variant& v);
// Directory of a job: its variant's, or its shader's ("unpruned/fresnel-schlick+exact_...").
std::string job_directory(const BuildJob& job);

// manifest.json of the specialized and branching modes: the material and scenes as above, then
// "shaders" (per job: the choices per axis, the selectors with their constant ids or block
// offsets, fold, files, reflection) and "variants" (per variant, sorted by scene and key: the
// shader directory that draws it and its selector values, placed; with freeze, its frozen
// SPIR-V).
void write_modes_manifest(const Material& material, BuildMode mode, bool freeze,
                          const std::vector<ManifestScene>& scenes,
                          const std::vector<BuildJob>& jobs, const std::vector<JobResult>& results,
                          const CausticsPasses& passes, const ReadJobFile& read,
                          const WriteText& write, const BindingMap* bindings = nullptr);

// The files of a directory by kind ("description", "glsl", "hlsl", "spirv", "glsl330",
// "essl300", "msl", "reflection"), as paths relative to the output directory.
nlohmann::ordered_json files_json(const std::string& dir, const std::vector<std::string>& names);
nlohmann::ordered_json files_json(const std::string& dir, const FileMap& files);

// Where a variant's frozen SPIR-V goes in its shader's directory: "glsl/frozen/<stem>.frag.spv".
std::string frozen_path(const std::string& language, const Variant& v);
struct FrozenVariant {
    std::string spirv; // the module's bytes; empty when freezing failed
    Diagnostics diagnostics;
    std::string content_hash;   // its build cache key
    bool cached = false;        // copied from the cache
    std::string cache_rejected; // non-empty: the entry failed verification (why), was rebuilt
};
// The one file of a frozen module's cache entry.
constexpr const char* kFrozenCacheFile = "frozen.spv";

// The variant's fragment SPIR-V of one language path (`module`, its optimised module;
// `description`, its shader's variant.json, which places the selectors) with the shader's selectors
// frozen to the variant's values (freeze_specialization(), one spirv-opt -O run), or a verified
// copy from `cache` (keyed by the module and the values).
FrozenVariant freeze_variant(const std::string& module, const std::string& description,
                             const ShaderChoices& shader, const Variant& v,
                             const std::string& language, const BuildCache& cache = {});

} // namespace watergen
