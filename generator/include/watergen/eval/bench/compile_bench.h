// The compile benchmark (`watergen bench compile`): the in-process toolchain against the same
// chain run through the command-line tools as processes, in the same run on the same shaders.
#pragma once

#include <string>
#include <vector>

#include "watergen/ir/core/diagnostic.h"

namespace watergen {

struct CompileBenchRow {
    std::string key;                            // the variant
    double in_process_ms = 0, processes_ms = 0; // median of the timed runs, all four shaders
    double ratio() const { return processes_ms / in_process_ms; }
};

struct CompileBench {
    std::vector<CompileBenchRow> rows; // pairwise covering variants, in their order
    // Medians over the rows.
    double median_in_process_ms = 0, median_processes_ms = 0, median_ratio = 0;
    std::string csv, json;   // compile.csv, compile.json
    Diagnostics diagnostics; // of the variant that failed to emit
    std::string error;       // a chain failed: "<variant key>: <what>"
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
};

// What:   for every pairwise covering variant, its GLSL and HLSL vertex and fragment shaders
//         through run_toolchain and through run_tool_process_chain, `repeat` times each,
//         alternating; the median of each.
// Output: one row per variant, or the first failure (the rows measured so far stay).
// Cost:   ~0.5 s per variant and repetition, nearly all of it in the processes; intermediate
//         files go to a directory under the system's temporary directory, removed at the end.
CompileBench run_compile_bench(int repeat);

} // namespace watergen
