// CPU evaluator bench: prints run_cpu_bench() (eval/bench/cpu_bench.h) as a table and writes it
// to cpu.csv and cpu.json.
#include <cstdio>

#include "commands.h"
#include "watergen/eval/bench/cpu_bench.h"

namespace watergen::cli {

namespace {

void print_ratio(const CpuBenchRatio& r) {
    std::printf("%-16s median %.3f, range %.3f..%.3f over %zu rounds\n", r.label.c_str(), r.median,
                r.lo, r.hi, r.rounds);
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
        const CpuBench bench = run_cpu_bench(o->size, o->rounds);
        if (!bench.ok()) return stop(bench.error, RunStatus::Failed);
        std::printf("%-16s %8s %10s %10s %10s %10s\n", "job", "threads", "median ms", "min ms",
                    "max ms", "us/pixel");
        for (const CpuBenchRow& r : bench.rows)
            std::printf("%-16s %8u %10.1f %10.1f %10.1f %10.3f\n", r.job.c_str(), r.threads,
                        r.median_ms, r.min_ms, r.max_ms, r.us_per_pixel);
        print_ratio(bench.aa);
        print_ratio(bench.one_thread);
        // The reference image's budget: the gold variant in float on every core at 1024x1024
        // within 3 s.
        if (o->size == 1024)
            std::printf("float at 1024x1024: %.2f s (budget 3 s)\n",
                        bench.rows.front().median_ms / 1000.0);
        std::printf("%s at %ux%u, synthetic scene, %zu live nodes, %u cores\n",
                    bench.variant.c_str(), o->size, o->size, bench.live_nodes, bench.cores);
        return write_bench_files(o->out, "cpu", bench.csv, bench.json) ? kOk : kFailed;
    };
}

} // namespace watergen::cli
