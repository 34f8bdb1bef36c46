// The CPU evaluator bench (`watergen bench cpu`): the gold variant's reference image on the
// CPU, per precision and thread count, timed in interleaved rounds, with an A/A pair (the same
// job twice) to show what the timer can resolve.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace watergen {

struct CpuBenchRow {
    std::string job;        // "float", "float A'", "float 1 thread", "double", "half"
    unsigned threads = 0;   // evaluator threads (every core, or one)
    std::vector<double> ms; // per round
    double median_ms = 0, min_ms = 0, max_ms = 0, us_per_pixel = 0;
};

// Paired ratios of two jobs' times, round by round.
struct CpuBenchRatio {
    std::string label;
    double median = 0, lo = 0, hi = 0;
    size_t rounds = 0;
};

struct CpuBench {
    std::string variant; // the key of accuracy_reference_variant()
    uint32_t size = 0;
    unsigned cores = 0;
    size_t live_nodes = 0; // of its fragment graph
    std::vector<CpuBenchRow> rows;
    CpuBenchRatio aa;         // "A/A' (same job)": float against float A'
    CpuBenchRatio one_thread; // "1 thread / all"
    std::string error;        // the evaluator failed
    std::string csv, json;    // cpu.csv, cpu.json
    bool ok() const { return error.empty(); }
};

// Cost: rounds x 5 evaluations of size x size pixels (about 30 us per pixel per thread in
// float, more in double and half).
CpuBench run_cpu_bench(uint32_t size, uint32_t rounds);

} // namespace watergen
