// Pruning benchmark as a library call (`watergen bench prune` prints it): per scene, a set of
// its distinct folded shaders against the same variants unpruned, drawn on the Vulkan runner
// over the synthetic scene conformed to the scene's facts, with the instrument of
// `watergen compare` (interleaved_timing.h): SPIR-V sizes, the steady draw time of pruned
// against unpruned paired by round with a 95% interval and an A/A check, and how far the
// images differ (GLSL, HLSL, CPU), and the instruction counts of both shaders under valgrind
// (draw_cost.h: the counting workers are watergen processes).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "watergen/eval/compare/prune_measure.h"
#include "watergen/eval/measure/gpu_target.h"
#include "watergen/eval/measure/interleaved_timing.h"

namespace watergen {

struct PruneBenchOptions {
    uint32_t size = 256;             // image width and height
    uint32_t rounds = 20, draws = 3; // interleaved timing: rounds x draws per shader
    size_t per_scene = 4;            // distinct shaders measured per scene; 0: all
    bool cost = false;               // count instructions per pixel under valgrind
    uint32_t cost_size = 64;         // of the count
    // The files the material ("": the built-in one) and each scene (by name) were loaded from:
    // the counting workers load them again.
    std::string material_path;
    std::map<std::string, std::string> scene_files;
    // AMD families whose ACO also compiles both shaders of every row (gpu_cost.h).
    std::vector<GpuTarget> gpu_targets;
};

struct PruneBenchRow {
    Variant variant;
    std::string short_key;        // the choices of the axes the material varies, without axis names
    PruneMeasurement measurement; // sizes and image differences
    RatioInterval time;           // pruned / unpruned steady draw, paired by round
    // Instructions per pixel of the steady draw under valgrind; 0: not counted.
    double cost_unpruned = 0, cost_pruned = 0;
    double cost_ratio() const { return cost_unpruned > 0 ? cost_pruned / cost_unpruned : 0; }
    double max_diff = 0; // over the GLSL, HLSL and CPU images
    // Per AMD target: ACO's fragment cost per pixel (loops weighted), unpruned and pruned.
    std::map<std::string, std::pair<double, double>> target_costs;
};

struct PruneBenchScene {
    std::string name;
    std::string notes;               // what conform_scene moved
    size_t distinct = 0;             // distinct folded shaders the scene has
    std::vector<PruneBenchRow> rows; // the measured ones (prune_bench_shaders), in plan order
    RatioInterval aa;                // the first unpruned shader timed against itself
    bool complete = false; // false when a measurement failed (the rows before it are kept)
    // Medians over the rows of pruned / unpruned (cost: 0 when not counted); the largest image
    // difference. Filled by summarise_prune_scene.
    double ir = 0, spirv = 0, spirv_opt = 0, time = 0, cost = 0, worst = 0;
    std::map<std::string, double> target_cost; // per AMD target: median pruned / unpruned
    bool timing_trustworthy() const { return aa.within(kAATolerance); }
};

struct PruneBenchResult {
    std::vector<PruneBenchScene> scenes; // in plan order; the last one incomplete on error
    std::string error;                   // "scene: key: why" of the failed measurement
    // The count's A/A: the first scene's first unpruned shader counted twice (two pipelines).
    double cost_aa = 0;
    std::string cost_error; // "scene: instruction count: why" (the tables are not made)
    std::string csv, json;  // prune.csv, prune.json, of the scenes measured
    bool ok() const { return error.empty(); }
    bool within(double tolerance) const; // every image difference is at most `tolerance`
};

// The variants whose folded shaders a scene's row set measures, and (in *distinct) how many
// distinct folded shaders the plan has. With a limit, a greedy cover first: each next shader
// is the one holding the most choices of the material's varying axes not yet measured (ties:
// plan order), then plan order; returned in plan order.
std::vector<Variant> prune_bench_shaders(const Material& material, const ScenePlan& plan,
                                         size_t limit, size_t* distinct);

void summarise_prune_scene(PruneBenchScene& scene);

// What:   per scene of `plans` (planned against `material`), builds each of
//         prune_bench_shaders' variants pruned and unpruned, times all of them interleaved
//         (GLSL path; ratios paired by round, the first unpruned shader's A/A), renders the
//         HLSL path once each and evaluates both graphs on the CPU in float to compare images.
//         With options.cost, then counts both shaders of every row (pruned: folded under the
//         scene's facts; unpruned: as composed; both in the scene's conformed synthetic scene).
// Cost:   per scene, 2 x shaders + 1 timed pipelines and 2 x shaders HLSL ones (lavapipe JIT,
//         0.1-0.5 s each), the timing rounds, 2 x shaders CPU evaluations; counting, about 5 s
//         of JIT under valgrind per shader.
PruneBenchResult bench_prune(VulkanRunner& runner, const Material& material,
                             const std::vector<ScenePlan>& plans, const PruneBenchOptions& options);

// Fills result.csv and result.json (prune.csv, prune.json) from the scenes measured, the
// incomplete one last (prune_bench_tables.cpp).
void add_prune_tables(const PruneBenchOptions& options, const std::string& device,
                      PruneBenchResult& result);

} // namespace watergen
