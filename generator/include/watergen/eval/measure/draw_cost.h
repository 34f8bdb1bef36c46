// A draw's load-free cost as a library call: the instructions lavapipe executes for it, counted
// under valgrind (draw_count.h) by counting workers (cost_worker.h), the `watergen` executable
// run again; so these calls count from within that executable only.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/measure/cost_worker.h"
#include "watergen/runtime/water_grid.h"

namespace watergen {

// What:   the steady draw of each variant's GLSL path at size x size in the named view, built
//         as `watergen render` builds it with the preset (and, with strict_half, a half one in
//         explicit 16-bit types), by key; a key given twice comes back a second time as
//         "<key>#2", each its own pipeline (an A/A pair). Every variant is counted in one of
//         up to one worker per hardware thread, all at once.
// Output: the counts, or nullopt and *error when a worker failed.
// Cost:   about 5 s of JIT under valgrind per variant.
std::optional<std::map<std::string, uint64_t>>
count_draw_costs(const std::vector<Variant>& variants, uint32_t size, const std::string& preset,
                 const std::string& view, std::string* error, bool strict_half = false,
                 const WaterGridDesc& grid = {});

// The same for a material's shaders (path "" = the built-in material) as a build ships them:
// composed by the material and, with a scene file, folded under its facts (unless `folded` is
// false: bench prune's unpruned side), drawn in the scene's conformed synthetic scene.
std::optional<std::map<std::string, uint64_t>>
count_material_costs(const std::string& material_path, const std::string& scene_path,
                     const std::vector<Variant>& variants, uint32_t size, std::string* error,
                     bool folded = true, const WaterGridDesc& grid = {});

// Each job's keys (VariantCountJob::keys: the steady draw of their GLSL paths, by label), every
// job in a valgrind run of its own (so each may have its own grid, size or view), up to one run
// per hardware thread at once. Output: per job, in order, its counts; nullopt and *error when a
// run failed.
std::optional<std::vector<std::map<std::string, uint64_t>>>
count_jobs(const std::vector<VariantCountJob>& jobs, std::string* error);

// One language path's counts over the runs: the smallest steady draw and JIT span ("first":
// pipeline creation through the first draw), and by how much the runs differ (percent).
struct PathCost {
    uint64_t draw = 0, first = 0;
    double draw_spread = 0, first_spread = 0;
};

struct VariantCost {
    std::array<std::optional<PathCost>, 2> paths; // GLSL, HLSL; nullopt: valgrind gave no count
    std::string error;                            // a run failed
    bool ok() const { return error.empty(); }
};

// `watergen cost`: the job's variant (its keys left empty) counted in `runs` valgrind runs one
// after another, each with its dumps in a directory of its own under `scratch`.
VariantCost count_variant_cost(const VariantCountJob& job, uint32_t runs,
                               const std::filesystem::path& scratch);

} // namespace watergen
