#include "watergen/eval/bench/cpu_bench.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/eval/bench/accuracy_bench.h"
#include "watergen/eval/measure/interleaved_timing.h" // median()
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/water/water_shader.h"

namespace watergen {

namespace {

struct Config {
    std::string name;
    EvalPrecision precision;
    unsigned threads; // 0 = one per core
};

CpuBenchRatio paired_ratio(const char* label, const std::vector<double>& a,
                           const std::vector<double>& b) {
    std::vector<double> r;
    for (size_t i = 0; i < a.size(); ++i)
        r.push_back(a[i] / b[i]);
    const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
    return {label, median(r), *lo, *hi, r.size()};
}

} // namespace

CpuBench run_cpu_bench(uint32_t size, uint32_t rounds) {
    CpuBench out;
    const Variant variant = accuracy_reference_variant();
    const WaterShader shader = build_water_shader(variant);
    const SyntheticScene scene = make_synthetic_scene(size, size);
    out.variant = variant.key();
    out.size = size;
    out.cores = std::max(1u, std::thread::hardware_concurrency());
    out.live_nodes = shader.fragment.live_nodes().size();
    // "float A" and "float A'" are the same job: their ratio is the timer's own spread.
    const std::vector<Config> configs = {{"float", EvalPrecision::Float, 0},
                                         {"float A'", EvalPrecision::Float, 0},
                                         {"float 1 thread", EvalPrecision::Float, 1},
                                         {"double", EvalPrecision::Double, 0},
                                         {"half", EvalPrecision::Half, 0}};
    std::vector<std::vector<double>> ms(configs.size());
    for (uint32_t r = 0; r < rounds; ++r)
        for (size_t c = 0; c < configs.size(); ++c) {
            EvalInputs in = scene.eval_inputs();
            in.threads = configs[c].threads;
            const auto t0 = std::chrono::steady_clock::now();
            const EvalResult result =
                evaluate_image(shader.fragment, "color", in, size, size, configs[c].precision);
            ms[c].push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count());
            if (!result.ok()) {
                out.error = "CPU evaluator: " + result.error;
                return out;
            }
        }
    const double pixels = double(size) * size;
    out.csv = "job,threads,median_ms,min_ms,max_ms,us_per_pixel\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (size_t c = 0; c < configs.size(); ++c) {
        CpuBenchRow row;
        row.job = configs[c].name;
        row.threads = configs[c].threads ? configs[c].threads : out.cores;
        row.ms = ms[c];
        row.median_ms = median(ms[c]);
        const auto [lo, hi] = std::minmax_element(ms[c].begin(), ms[c].end());
        row.min_ms = *lo;
        row.max_ms = *hi;
        row.us_per_pixel = row.median_ms * 1000.0 / pixels;
        out.csv += fmt::format("\"{}\",{},{:.2f},{:.2f},{:.2f},{:.4f}\n", row.job, row.threads,
                               row.median_ms, row.min_ms, row.max_ms, row.us_per_pixel);
        rows.push_back({{"job", row.job},
                        {"threads", row.threads},
                        {"ms", row.ms},
                        {"median_ms", row.median_ms}});
        out.rows.push_back(std::move(row));
    }
    out.aa = paired_ratio("A/A' (same job)", ms[0], ms[1]);
    out.one_thread = paired_ratio("1 thread / all", ms[2], ms[0]);
    const nlohmann::ordered_json doc = {
        {"variant", out.variant}, {"size", size}, {"cores", out.cores}, {"rows", rows}};
    out.json = doc.dump(2) + "\n";
    return out;
}

} // namespace watergen
