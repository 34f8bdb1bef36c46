// Accuracy bench: prints bench_accuracy() (eval/bench/accuracy_bench.h) as a table and writes it
// to accuracy.csv and accuracy.json.
#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/bench/accuracy_bench.h"

namespace watergen::cli {

namespace {

struct Options {
    AccuracyBenchRequest request;
    std::string out = "out/bench";
    RunnerSetup runner;
    std::vector<std::string> targets;
};

// With several targets: each row's cost ratio to its gold per target, beside its error, and
// where the targets rank it the other way.
void print_target_ratios(const AccuracyBench& bench) {
    std::printf("\ncost / the axis' gold per target (lavapipe: valgrind instructions; AMD: ACO "
                "fragment instructions, loops weighted):\n%-11s %-26s",
                "axis", "choice");
    for (const std::string& t : bench.targets)
        std::printf(" %9s", t.c_str());
    std::printf(" %10s  %s\n", "dE p99", "where the targets disagree");
    for (const AccuracyRow& r : bench.rows) {
        if (r.skipped() || r.gold) continue;
        std::printf("%-11s %-26s", r.axis.c_str(), r.choice.c_str());
        for (const std::string& t : bench.targets) {
            const double ratio = bench.cost_ratio(r, t);
            if (ratio > 0)
                std::printf(" %9.3f", ratio);
            else
                std::printf(" %9s", "n/a");
        }
        const std::string error =
            r.approximation() ? fmt::format("{:.3f}", r.worst.ciede2000_p99) : "(model)";
        std::printf(" %10s  %s\n", error.c_str(), bench.disagreement(r).c_str());
    }
}

void print_rows(const AccuracyBench& bench) {
    std::printf("%-11s %-26s %-13s %10s %7s %22s %9s %10s  %s\n", "axis", "choice", "relation",
                "cost/px", "cost", "time [95% CI]", "max abs", "dE p99", "worst view");
    for (const AccuracyRow& r : bench.rows) {
        const std::string choice = r.choice + (r.gold ? " (gold)" : "");
        if (r.skipped()) {
            std::printf("%-11s %-26s %s\n", r.axis.c_str(), choice.c_str(), r.note.c_str());
            continue;
        }
        const double g = bench.gold_cost(r.axis);
        const std::string time = interval_text(r.time);
        const std::string kind = r.relation.substr(0, r.relation.find(' '));
        if (r.gold || r.approximation())
            std::printf("%-11s %-26s %-13s %10.1f %6.3fx %22s %9.3g %10.3f  %s\n", r.axis.c_str(),
                        choice.c_str(), kind.c_str(), r.cost_per_pixel,
                        g > 0 ? r.cost_per_pixel / g : 0.0, time.c_str(), r.worst.max_abs,
                        r.worst.ciede2000_p99, r.worst_view.c_str());
        else // a different model: its cost, not an error
            std::printf("%-11s %-26s %-13s %10.1f %6.3fx %22s %20s\n", r.axis.c_str(),
                        choice.c_str(), "different", r.cost_per_pixel,
                        g > 0 ? r.cost_per_pixel / g : 0.0, time.c_str(), "(different model)");
    }
    for (const AccuracyAxis& a : bench.axes)
        std::printf("A/A %-11s %.3f [%.3f, %.3f]%s\n", a.axis.c_str(), a.aa.ratio, a.aa.lo, a.aa.hi,
                    a.aa.within(kAATolerance) ? "" : "  NOT within +-3%: times untrusted");
}

} // namespace

Runner add_bench_accuracy_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<Options>();
    AccuracyBenchRequest& r = o->request;
    r.cost = true; // unless --no-cost
    app.add_option("--size", r.size, "image width and height (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--rounds", r.rounds, "timing rounds, interleaved (default 20)")
        ->check(CLI::Range(3, 1000));
    add_instrument_options(app, r.draws, r.cost_size, r.cost);
    app.add_option("--out", o->out,
                   "directory for accuracy.csv and accuracy.json (default out/bench)");
    add_runner_options(app, o->runner);
    add_target_option(app, o->targets);
    return [o, &common]() {
        const auto targets = resolve_targets(o->targets);
        if (!targets) return kUsage;
        AccuracyBenchRequest& request = o->request;
        request.cost = request.cost && has_lavapipe(*targets);
        request.gpu_targets = amd_targets(*targets);
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const AccuracyBenchRequest& r = o->request;
        const AccuracyBench bench = bench_accuracy(*runner, r);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        print_rows(bench);
        if (bench.targets.size() > 1) print_target_ratios(bench);
        std::printf("reference: %s; %ux%u over %zu views, %u rounds x %u draws, %s; cost: "
                    "instructions per pixel, %ux%u beach view\n",
                    bench.reference.key().c_str(), r.size, r.size, bench.views.size(), r.rounds,
                    r.draws, runner->device_info().name.c_str(), r.cost_size, r.cost_size);
        return write_bench_files(o->out, "accuracy", bench.csv, bench.json) ? kOk : kFailed;
    };
}

} // namespace watergen::cli
