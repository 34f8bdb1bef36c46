// The accuracy benchmark (`watergen bench accuracy`): on every axis that has a gold choice, each
// cheaper choice against the gold, rendered in the same run: GPU time ratio and image error.
#pragma once

#include <string>
#include <vector>

#include "watergen/render/variant_render.h"
#include "watergen/water/variant.h"

namespace watergen {

struct AccuracyRow {
    std::string axis, choice;
    bool gold = false;
    double steady_ms = 0, time_ratio = 0;
    size_t instructions =
        0; // optimised fragment SPIR-V, GLSL path: a cost proxy free of timing noise
    ImageErrorStats error; // against the gold image of the same axis
    std::string note;      // why the row was skipped, or how its error was measured
    bool skipped() const { return !note.empty() && steady_ms == 0; }
};

struct AccuracyBench {
    std::vector<AccuracyRow> rows; // axes in registry order, the gold first within each
    Diagnostics diagnostics;       // of the variant that failed to build
    std::string error;             // a render failed: "<variant key>: <what>"
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
};

// The variant every row differs from in one axis: the gold choice where an axis has one, and
// Gerstner waves (analytic normals need a closed-form wave model).
Variant accuracy_reference_variant();

// What:   per axis with a gold choice, the reference with each of the axis' choices, built,
//         rendered on `runner` over the synthetic scene of `size` x `size` and compared with the
//         gold; the gold is rendered again right after each candidate and the time ratio taken
//         against that. The precision axis' half row is built strict half (EmitOptions), so
//         lavapipe computes it in 16-bit arithmetic; its note gives the CPU half model's figures.
// Output: the rows, or the first failure (the rows measured so far stay).
// Cost:   about two variant builds and three renders of `draws` timed draws per choice.
AccuracyBench run_accuracy_bench(VulkanRunner& runner, uint32_t size, uint32_t draws);

} // namespace watergen
