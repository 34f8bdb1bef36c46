// Agreement bench: prints run_agreement_bench() (eval/bench/agreement_bench.h) as a table and
// writes it to agreement.csv and agreement.json; exits 1 when a pixel is over its allowance.
#include <algorithm>
#include <cstdio>

#include "commands.h"
#include "watergen/eval/bench/agreement_bench.h"

namespace watergen::cli {

namespace {

void print_rows(const AgreementBench& bench) {
    std::printf("%-4s %10s %10s %10s %10s %10s %9s %9s %10s\n", "#", "glsl-hlsl", "gpu-float",
                "hlsl-float", "gpu-double", "flt-double", "over tol", "unexpl.", "max bound");
    for (size_t i = 0; i < bench.rows.size(); ++i) {
        const AgreementBenchRow& r = bench.rows[i];
        std::printf("%-4zu %10.3g %10.3g %10.3g %10.3g %10.3g %9llu %9llu %10.3g\n", i + 1,
                    r.glsl_vs_hlsl, r.vs_cpu_float[0], r.vs_cpu_float[1], r.glsl_vs_cpu_double,
                    r.cpu_float_vs_double,
                    static_cast<unsigned long long>(
                        std::max(r.agreement[0].over_tolerance, r.agreement[1].over_tolerance)),
                    static_cast<unsigned long long>(
                        std::max(r.agreement[0].over_bound, r.agreement[1].over_bound)),
                    r.agreement[0].max_bound);
    }
    for (size_t i = 0; i < bench.rows.size(); ++i)
        std::printf("%zu: %s%s%s\n", i + 1, bench.rows[i].key.c_str(),
                    bench.rows[i].cause.empty() ? "" : "\n    worst pixel most from ",
                    bench.rows[i].cause.c_str());
}

} // namespace

Runner add_bench_agreement_command(CLI::App& app, const Common& common) {
    struct Options {
        uint32_t size = 512;
        double tolerance = kAgreementTolerance;
        std::string out = "out/bench";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 512)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--tolerance", o->tolerance,
                   "GPU against CPU float beyond each pixel's float error bound (default 5e-5)")
        ->check(finite_range(0, 1e6));
    app.add_option("--out", o->out,
                   "directory for agreement.csv and agreement.json (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const AgreementBench bench = run_agreement_bench(*runner, o->size, o->tolerance);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        print_rows(bench);
        uint64_t unexplained = 0;
        double worst_float = 0, worst_double = 0;
        for (const AgreementBenchRow& r : bench.rows) {
            unexplained += std::max(r.agreement[0].over_bound, r.agreement[1].over_bound);
            worst_float = std::max({worst_float, r.vs_cpu_float[0], r.vs_cpu_float[1]});
            worst_double = std::max(worst_double, r.glsl_vs_cpu_double);
        }
        std::printf("%ux%u, synthetic scene (beach view), %s: worst gpu vs cpu float %.3g, vs cpu "
                    "double %.3g; %llu pixel%s over %.3g plus their float error bound\n",
                    o->size, o->size, runner->device_info().name.c_str(), worst_float, worst_double,
                    static_cast<unsigned long long>(unexplained), unexplained == 1 ? "" : "s",
                    o->tolerance);
        if (!write_bench_files(o->out, "agreement", bench.csv, bench.json)) return kFailed;
        return unexplained == 0 ? kOk : kFailed;
    };
}

} // namespace watergen::cli
