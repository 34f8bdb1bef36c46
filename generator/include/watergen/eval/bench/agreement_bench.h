// The agreement bench (`watergen bench agreement`): every variant of the pairwise covering set
// drawn through both language paths at one size and compared with the CPU evaluator in float
// and in double, pixel by pixel within the tolerance plus the float error expected at each
// pixel (variant_render.h's float_bound). The figures users ask of the oracle at the
// resolutions they render at.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "watergen/eval/draw/variant_render.h"

namespace watergen {

struct AgreementBenchRow {
    std::string key;
    double glsl_vs_hlsl = 0;
    std::array<double, 2> vs_cpu_float{}; // max abs, GLSL and HLSL
    double glsl_vs_cpu_double = 0, cpu_float_vs_double = 0;
    std::array<Agreement, 2> agreement;
    uint64_t gpu_nan_inf = 0;
    // With a pixel over the tolerance: the operation whose float rounding moves the worst one
    // most (attribute_float_error), "origin op(operands)".
    std::string cause;
};

struct AgreementBench {
    uint32_t size = 0;
    double tolerance = kAgreementTolerance;
    std::vector<AgreementBenchRow> rows; // the covering set, in its order
    std::string csv, json;               // agreement.csv, agreement.json
    Diagnostics diagnostics;             // of a build that failed
    std::string error;                   // "<variant key>: <what>"
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
};

// What:   render_variant of every covering variant over the synthetic scene of size x size,
//         with the CPU float and double images and the float error bound.
// Output: a row per variant, or the first failure (the rows so far stay).
// Cost:   per variant two pipelines (JIT) and six CPU evaluations (float, double, the bound's
//         four), and one evaluation of a quad per operation to trace a pixel over the
//         tolerance: about 4 s at 512x512 and 20 s at 1024x1024 on this project's 2-core
//         machine.
AgreementBench run_agreement_bench(VulkanRunner& runner, uint32_t size, double tolerance);

} // namespace watergen
