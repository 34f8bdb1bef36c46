// CPU evaluator bench: the gold variant's reference image on the CPU, per precision and thread
// count, timed in interleaved rounds, with an A/A pair to show what the timer can resolve.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/eval/bench/accuracy_bench.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/ir/cpu_evaluator.h"
#include "watergen/pipeline/compile_bench.h"
#include "watergen/water/water_shader.h"

namespace watergen::cli {

namespace {

struct Config {
    std::string name;
    EvalPrecision precision;
    unsigned threads; // 0 = one per core
};

// Paired ratios of two jobs' times, round by round: the A/A one says how large a difference can
// be noise.
void print_ratio(const char* label, const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> r;
    for (size_t i = 0; i < a.size(); ++i)
        r.push_back(a[i] / b[i]);
    const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
    std::printf("%-16s median %.3f, range %.3f..%.3f over %zu rounds\n", label, median(r), *lo, *hi,
                r.size());
}

} // namespace

Runner add_bench_cpu_command(CLI::App& app, const Common&) {
    struct Options {
        uint32_t size = 1024, rounds = 3;
        std::string out = "out/bench";
    };
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 1024)")
        ->check(CLI::Range(16, 4096));
    app.add_option("--rounds", o->rounds,
                   "interleaved rounds; medians and ranges are over them (default 3)")
        ->check(CLI::Range(1, 100));
    app.add_option("--out", o->out, "directory for cpu.csv and cpu.json (default out/bench)");
    return [o]() {
        const Variant variant = accuracy_reference_variant();
        const WaterShader shader = build_water_shader(variant);
        const SyntheticScene scene = make_synthetic_scene(o->size, o->size);
        const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
        // "float A" and "float A'" are the same job: their ratio is the timer's own spread.
        const std::vector<Config> configs = {{"float", EvalPrecision::Float, 0},
                                             {"float A'", EvalPrecision::Float, 0},
                                             {"float 1 thread", EvalPrecision::Float, 1},
                                             {"double", EvalPrecision::Double, 0},
                                             {"half", EvalPrecision::Half, 0}};
        std::vector<std::vector<double>> ms(configs.size());
        for (uint32_t r = 0; r < o->rounds; ++r)
            for (size_t c = 0; c < configs.size(); ++c) {
                EvalInputs in = scene.eval_inputs();
                in.threads = configs[c].threads;
                const auto t0 = std::chrono::steady_clock::now();
                const EvalResult result = evaluate_image(shader.fragment, "color", in, o->size,
                                                         o->size, configs[c].precision);
                ms[c].push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
                if (!result.ok()) {
                    std::fprintf(stderr, "watergen: error: CPU evaluator: %s\n",
                                 result.error.c_str());
                    return kFailed;
                }
            }
        const double pixels = double(o->size) * o->size;
        std::printf("%-16s %8s %10s %10s %10s %10s\n", "job", "threads", "median ms", "min ms",
                    "max ms", "us/pixel");
        std::string csv = "job,threads,median_ms,min_ms,max_ms,us_per_pixel\n";
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        for (size_t c = 0; c < configs.size(); ++c) {
            const unsigned threads = configs[c].threads ? configs[c].threads : cores;
            const double med = median(ms[c]);
            const auto [lo, hi] = std::minmax_element(ms[c].begin(), ms[c].end());
            std::printf("%-16s %8u %10.1f %10.1f %10.1f %10.3f\n", configs[c].name.c_str(), threads,
                        med, *lo, *hi, med * 1000.0 / pixels);
            csv += fmt::format("\"{}\",{},{:.2f},{:.2f},{:.2f},{:.4f}\n", configs[c].name, threads,
                               med, *lo, *hi, med * 1000.0 / pixels);
            rows.push_back({{"job", configs[c].name},
                            {"threads", threads},
                            {"ms", ms[c]},
                            {"median_ms", med}});
        }
        print_ratio("A/A' (same job)", ms[0], ms[1]);
        print_ratio("1 thread / all", ms[2], ms[0]);
        // The reference image's budget: the gold variant in float on every core at 1024x1024
        // within 3 s.
        if (o->size == 1024)
            std::printf("float at 1024x1024: %.2f s (budget 3 s)\n", median(ms[0]) / 1000.0);
        std::printf("%s at %ux%u, synthetic scene, %zu live nodes, %u cores\n",
                    variant.key().c_str(), o->size, o->size, shader.fragment.live_nodes().size(),
                    cores);
        const nlohmann::ordered_json doc = {
            {"variant", variant.key()}, {"size", o->size}, {"cores", cores}, {"rows", rows}};
        return write_bench_files(o->out, "cpu", csv, doc.dump(2) + "\n") ? kOk : kFailed;
    };
}

} // namespace watergen::cli
