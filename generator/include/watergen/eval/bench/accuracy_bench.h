// The accuracy benchmark (`watergen bench accuracy`): on every axis that has a gold choice, each
// other choice against the gold, measured with the instrument of `watergen compare`
// (compare_run.h): image error over the named views, draw time interleaved with an A/A check.
// An approximation of the gold gets an error; a choice that is a different model (sines
// against Gerstner, no highlight against a GGX lobe) gets its cost and "different model".
#pragma once

#include <map>
#include <string>
#include <vector>

#include "watergen/eval/compare/compare_run.h"
#include "watergen/eval/measure/gpu_target.h"

namespace watergen {

struct AccuracyRow {
    std::string axis, choice;
    Variant variant; // the reference with this choice (waves rows: detail-map normals)
    bool gold = false;
    std::string relation; // "reference", "approximates (...)", "different model (...)"
    bool approximation() const { return relation.rfind("approximates", 0) == 0; }
    RatioInterval time;            // steady draw / the gold's, interleaved in the first view
    size_t spirv_instructions = 0; // optimised fragment SPIR-V, GLSL path
    double cost_per_pixel = 0;     // instructions per pixel under valgrind (bench_accuracy)
    // Per AMD target: ACO's fragment instructions per pixel, loops weighted (gpu_cost.h).
    std::map<std::string, double> target_costs;
    ImageErrorStats worst;  // over the views: each figure's worst view
    std::string worst_view; // the view of the worst p99 dE00
    std::string note;       // why the row was skipped, or how it was built
    bool skipped() const { return !note.empty() && spirv_instructions == 0; }
};

struct AccuracyAxis {
    std::string axis;
    Variant gold;     // the reference variant with the axis' gold
    RatioInterval aa; // the gold timed against a second pipeline of itself
};

struct AccuracyBench {
    Variant reference;             // accuracy_reference_variant()
    std::vector<AccuracyRow> rows; // axes in registry order, the gold first within each
    std::vector<AccuracyAxis> axes;
    std::vector<std::string> views;
    std::string csv, json;   // accuracy.csv, accuracy.json (bench_accuracy)
    Diagnostics diagnostics; // of the variant that failed to build
    std::string error;       // a render failed: "<variant key>: <what>"; or the instruction count
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
    // The instructions per pixel of the axis' gold row (0: none, or not counted).
    double gold_cost(const std::string& axis) const;
    // The cost targets measured: "lavapipe" (when counted), then the AMD ones.
    std::vector<std::string> targets;
    // The row's cost on `target` over its axis' gold's (0: not measured).
    double cost_ratio(const AccuracyRow& row, const std::string& target) const;
    // Where the targets rank the row and its gold the other way: "cheaper than the gold on
    // rdna2, gcn4; dearer on lavapipe" (a ratio within 0.5% of 1 is a tie, on neither side);
    // "" when they agree.
    std::string disagreement(const AccuracyRow& row) const;
};

// The variant every row differs from in one axis: the gold choice where an axis has one, and
// Gerstner waves (analytic normals need a closed-form wave model).
Variant accuracy_reference_variant();

// What:   per axis with a gold choice, the reference with each of the axis' choices (the half
//         row built strict half, so lavapipe computes it in 16-bit arithmetic) compared with
//         the gold over `views` (GLSL path only) and timed against it (`rounds` x `draws`).
// Output: the rows, or the first failure (the rows measured so far stay).
// Cost:   per axis, a pipeline per choice and view plus the timing rounds.
AccuracyBench run_accuracy_bench(VulkanRunner& runner,
                                 const std::vector<std::pair<std::string, SyntheticScene>>& views,
                                 uint32_t rounds, uint32_t draws);

struct AccuracyBenchRequest {
    uint32_t size = 256, rounds = 20, draws = 3; // every view at size x size; timing
    bool cost = false;                           // count instructions per pixel (valgrind)
    uint32_t cost_size = 64;                     // of the count, in the beach view
    std::vector<GpuTarget> gpu_targets;          // AMD families' ACO statistics too
};

// `watergen bench accuracy`: run_accuracy_bench over every view of the synthetic scene, each
// measured row's instructions per pixel counted (draw_cost.h; the half row strict half, as it
// is timed), and the tables. Cost: run_accuracy_bench's, plus about 5 s of JIT under valgrind
// per variant counted.
AccuracyBench bench_accuracy(VulkanRunner& runner, const AccuracyBenchRequest& request);

} // namespace watergen
