// Accuracy bench: on every axis that has a gold choice, each cheaper choice against the gold,
// rendered in the same run: GPU time ratio and image error.
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/render/accuracy_bench.h"

namespace watergen::cli {

Runner add_bench_accuracy_command(CLI::App& app, const Common& common) {
    struct Options {
        uint32_t size = 256, draws = 15;
        std::string out = "out/bench";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--draws", o->draws, "timed draws per variant; the median is used (default 15)")
        ->check(CLI::Range(3, 1000));
    app.add_option("--out", o->out,
                   "directory for accuracy.csv and accuracy.json (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const AccuracyBench bench = run_accuracy_bench(*runner, o->size, o->draws);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        std::printf("%-11s %-33s %7s %10s %8s %11s %11s %9s %9s\n", "axis", "choice", "instrs",
                    "steady ms", "time", "max abs", "rmse", "dE mean", "dE p99");
        std::string csv = "axis,choice,gold,spirv_instructions,steady_ms,time_ratio,max_abs,rmse,"
                          "ciede2000_mean,ciede2000_p99,note\n";
        nlohmann::ordered_json json = nlohmann::ordered_json::array();
        for (const auto& r : bench.rows) {
            if (r.skipped()) {
                std::printf("%-11s %-33s %s\n", r.axis.c_str(), r.choice.c_str(), r.note.c_str());
            } else {
                std::printf("%-11s %-33s %7zu %10.3f %7.2fx %11.3g %11.3g %9.3f %9.3f%s\n",
                            r.axis.c_str(), (r.choice + (r.gold ? " (gold)" : "")).c_str(),
                            r.instructions, r.steady_ms, r.time_ratio, r.error.max_abs,
                            r.error.rmse, r.error.ciede2000_mean, r.error.ciede2000_p99,
                            r.note.empty() ? "" : "  *");
            }
            csv += fmt::format("{},{},{},{},{:.4f},{:.3f},{:.6g},{:.6g},{:.4f},{:.4f},\"{}\"\n",
                               r.axis, r.choice, r.gold, r.instructions, r.steady_ms, r.time_ratio,
                               r.error.max_abs, r.error.rmse, r.error.ciede2000_mean,
                               r.error.ciede2000_p99, r.note);
            json.push_back({{"axis", r.axis},
                            {"choice", r.choice},
                            {"gold", r.gold},
                            {"spirv_instructions", r.instructions},
                            {"steady_ms", r.steady_ms},
                            {"time_ratio", r.time_ratio},
                            {"max_abs", r.error.max_abs},
                            {"rmse", r.error.rmse},
                            {"ciede2000_mean", r.error.ciede2000_mean},
                            {"ciede2000_p99", r.error.ciede2000_p99},
                            {"note", r.note}});
        }
        for (const auto& r : bench.rows)
            if (!r.skipped() && !r.note.empty())
                std::printf("* %s=%s: %s\n", r.axis.c_str(), r.choice.c_str(), r.note.c_str());
        std::printf("reference: %s\n%ux%u, median of %u timed draws, %s; Mesa shader cache %s\n",
                    accuracy_reference_variant().key().c_str(), o->size, o->size, o->draws,
                    runner->device_info().name.c_str(), cache.c_str());
        nlohmann::ordered_json doc = {{"reference", accuracy_reference_variant().key()},
                                      {"size", o->size},
                                      {"draws", o->draws},
                                      {"device", runner->device_info().name},
                                      {"rows", json}};
        if (!write_bench_files(o->out, "accuracy", csv, doc.dump(2) + "\n")) return kFailed;
        return kOk;
    };
}

} // namespace watergen::cli
