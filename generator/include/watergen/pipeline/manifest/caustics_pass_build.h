// The companion caustics pass of `watergen build`. A variant with caustics=area_ratio or
// photon_splat samples caustics_map, which the engine draws each frame with the pass of
// build_caustics_pass(method, wave model). The pass depends on those two only (precision and
// every other axis leave it alone; the material's preset and parameter settings give its
// defaults and ranges, one set per build), so a build writes each pass it needs once, under
// passes/caustics-<method>-<wave model>/, validated and cross-compiled like a variant, and each
// variant's manifest entry points at it with the draw the engine must make.
//
// The pass is not folded by the scenes: one pass serves every scene. Where a scene fixed a
// parameter the pass reads (the water variant folded it into a constant), the variant's entry
// carries the value in "values", and the engine sets it in the pass's uniform block.
#pragma once

#include <array>
#include <compare>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "watergen/caustics/caustics_pass.h"
#include "watergen/pipeline/cache/build_cache.h"
#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/plan/material.h"

namespace watergen {

struct CausticsPassKey {
    CausticsMethod method = CausticsMethod::AreaRatio;
    std::string wave_model; // the variant's waves choice: sum_of_sines or gerstner
    auto operator<=>(const CausticsPassKey&) const = default;
};

// The pass a variant draws its caustics_map with; nullopt for caustics none and texture.
std::optional<CausticsPassKey> caustics_pass_for(const Variant& v);

// Where the pass's files go in the output: "passes/caustics-area_ratio-gerstner".
std::string caustics_pass_directory(const CausticsPassKey& key);

// The name of a scene that would clash with the passes' directory.
constexpr const char* kPassesDirectory = "passes";

struct CausticsPassBuild {
    CausticsPass pass;
    std::array<LanguageBuild, 2> languages; // GLSL, HLSL
    Diagnostics diagnostics;
    // Every target's files relative to the pass directory (<lang>/caustics.<stage>.*, pass.json);
    // empty when the pass failed.
    FileMap files;
    std::string content_hash;   // its build cache key
    bool cached = false;        // files copied from the cache: `languages` hold the sources only
    std::string cache_rejected; // non-empty: the entry failed verification (why), was rebuilt
    bool ok() const { return !has_errors(diagnostics); }
};

// Builds the pass with the material's preset and parameter settings: both languages emitted,
// validated, optimised, cross-compiled and reflected as a variant is, and pass.json (the
// uniform block as variant.json lists one, the vertex input, the draw). Deterministic;
// about 0.1 s, or a verified copy from `cache` (keyed like a variant: the emitted sources, the
// interface, its slots and the toolchain versions). `bindings`: null for the default map.
CausticsPassBuild build_caustics_pass_files(const Material& material, const CausticsPassKey& key,
                                            const BuildCache& cache = {},
                                            const BindingMap* bindings = nullptr);

using CausticsPasses = std::map<CausticsPassKey, CausticsPassBuild>;

struct PassesOutput {
    CausticsPasses passes;
    // passes/<pass>/<file> for the union of the targets of the variants drawn with each pass.
    FileMap files;
    size_t failed = 0;
    size_t failed_by_map = 0;   // of those, failed only on the binding map (bad input)
    size_t cached = 0;          // copied from the build cache
    Diagnostics cache_rejected; // one warning per entry that failed verification (rebuilt)
    Diagnostics diagnostics;
};

// The passes the variants of the jobs need (a shader of the specialized and branching modes:
// those of every variant it serves), each built once on `options.threads` workers, or copied
// from `options.cache`. A build makes them before its jobs (its manifest's entries point at
// them); it publishes nothing if a job fails, so the passes of jobs that fail are not missed.
PassesOutput build_needed_passes(const Material& material, const JobList& jobs,
                                 const BuildOptions& options);

// A water variant's "passes" entry: {"caustics": {method, wave_model, directory, files (those
// `targets` keep), draw, values}}. `folded` is what the variant's scene folded; the map's side
// ("draw"."texels") is caustics_map_texels as the variant has it. Null JSON for a variant
// without a pass.
nlohmann::ordered_json passes_entry(const Material& material, const Variant& v,
                                    const std::vector<Target>& targets,
                                    const std::map<std::string, std::vector<double>>& folded,
                                    const CausticsPasses& passes);

} // namespace watergen
