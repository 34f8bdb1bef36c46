// Half bench: prints run_half_bench() (eval/bench/half_bench.h) as a table and writes it to
// half.csv and half.json.
#include <cstdio>

#include "commands.h"
#include "watergen/eval/bench/half_bench.h"

namespace watergen::cli {

namespace {

void print_row(size_t i, const HalfBenchRow& r) {
    const HalfAgreement &g = r.vs_cpu_half[0], &h = r.vs_cpu_half[1];
    const uint64_t nan_inf = r.vs_full[0].nan_inf_pixels + r.vs_full[1].nan_inf_pixels;
    std::printf("%-4zu %8.2f %8.2f %8lld %8.2f %8.2f %8lld %9.3g %9.4f %9.4f %9.3g %9.4f "
                "%9.4f %8llu\n",
                i + 1, percent(g.equal, g.values), percent(g.within_1, g.values),
                static_cast<long long>(g.max_ulps), percent(h.equal, h.values),
                percent(h.within_1, h.values), static_cast<long long>(h.max_ulps),
                r.vs_full[0].max_abs, r.vs_full[0].ciede2000_mean, r.vs_full[0].ciede2000_p99,
                r.cpu_half_vs_full.max_abs, r.cpu_half_vs_full.ciede2000_mean,
                r.cpu_half_vs_full.ciede2000_p99, static_cast<unsigned long long>(nan_inf));
}

} // namespace

Runner add_bench_half_command(CLI::App& app, const Common& common) {
    struct Options {
        uint32_t size = 256, draws = 3;
        std::string out = "out/bench";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--draws", o->draws, "timed draws per render (default 3)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--out", o->out, "directory for half.csv and half.json (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        if (!has_float16(*runner, "")) return kNoDevice;
        const HalfBench bench = run_half_bench(*runner, o->size, o->draws);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        std::printf("%-4s %26s %26s %29s %29s %8s\n", "", "glsl vs cpu half", "hlsl vs cpu half",
                    "glsl vs full precision", "cpu half vs full", "NaN/Inf");
        std::printf("%-4s %8s %8s %8s %8s %8s %8s %9s %9s %9s %9s %9s %9s %8s\n", "#", "equal%",
                    "<=1ulp%", "max ulp", "equal%", "<=1ulp%", "max ulp", "max abs", "dE mean",
                    "dE p99", "max abs", "dE mean", "dE p99", "gpu");
        for (size_t i = 0; i < bench.rows.size(); ++i)
            print_row(i, bench.rows[i]);
        for (size_t i = 0; i < bench.rows.size(); ++i)
            std::printf("%zu: %s\n", i + 1, bench.rows[i].key.c_str());
        std::printf("%ux%u, synthetic scene, %s; values compared as binary16 (R, G, B); full "
                    "precision = the variant at precision=full on the GPU (GLSL)\n",
                    o->size, o->size, runner->device_info().name.c_str());
        return write_bench_files(o->out, "half", bench.csv, bench.json) ? kOk : kFailed;
    };
}

} // namespace watergen::cli
