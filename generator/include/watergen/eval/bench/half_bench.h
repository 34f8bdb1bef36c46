// The half bench (`watergen bench half`): the covering set's half variants rendered in 16-bit
// arithmetic on the GPU (strict half, half_render.h), against the CPU half model and against
// each variant at full precision.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "watergen/eval/draw/half_render.h"

namespace watergen {

// One variant: the figures of its HalfRender, without the images.
struct HalfBenchRow {
    std::string key;
    std::array<HalfAgreement, 2> vs_cpu_half; // GLSL, HLSL strict half against the CPU model
    std::array<double, 2> max_abs_vs_cpu_half{};
    std::array<ImageErrorStats, 2> vs_full; // against the variant at precision=full (GPU)
    ImageErrorStats cpu_half_vs_full;       // the CPU emulation's estimate of the same
};

struct HalfBench {
    uint32_t size = 0;
    std::vector<HalfBenchRow> rows; // the covering set's half variants, in its order
    std::string csv, json;          // half.csv, half.json
    Diagnostics diagnostics;        // of a build that failed
    std::string error;              // "<variant key>: <what>"
    bool ok() const { return error.empty() && !has_errors(diagnostics); }
};

// Percent of `whole`, 0 for none.
double percent(uint64_t part, uint64_t whole);

// What:   render_strict_half of every precision=half variant of the pairwise covering set over
//         the synthetic scene of `size` x `size`, one after another on `runner` (a device with
//         shaderFloat16), and the tables.
// Output: a row per variant, or the first failure (the rows so far stay).
// Cost:   per variant, four pipelines (JIT) and one CPU half evaluation (about 2.5 s at 256^2).
HalfBench run_half_bench(VulkanRunner& runner, uint32_t size, uint32_t draws);

} // namespace watergen
