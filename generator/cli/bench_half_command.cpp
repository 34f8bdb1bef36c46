// Half bench: the covering set's half variants rendered in 16-bit arithmetic on the GPU (strict
// half), against the CPU half model and against each variant at full precision.
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/eval/draw/half_render.h"

namespace watergen::cli {

namespace {

double percent(uint64_t part, uint64_t whole) {
    return whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

nlohmann::ordered_json agreement_json(const HalfAgreement& a, double max_abs) {
    return {{"values", a.values},
            {"equal", a.equal},
            {"within_1_ulp", a.within_1},
            {"max_ulps", a.max_ulps},
            {"max_abs", max_abs}};
}

nlohmann::ordered_json error_json(const ImageErrorStats& s) {
    return {{"max_abs", s.max_abs},
            {"ciede2000_mean", s.ciede2000_mean},
            {"ciede2000_p99", s.ciede2000_p99},
            {"nan_inf_pixels", s.nan_inf_pixels}};
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
        if (!runner->device_info().shader_float16) {
            std::fprintf(stderr, "watergen: error: %s has no shaderFloat16\n",
                         runner->device_info().name.c_str());
            return kNoDevice;
        }
        const HalfBench bench = run_half_bench(*runner, o->size, o->draws);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        std::printf("%-4s %26s %26s %29s %29s %8s\n", "", "glsl vs cpu half", "hlsl vs cpu half",
                    "glsl vs full precision", "cpu half vs full", "NaN/Inf");
        std::printf("%-4s %8s %8s %8s %8s %8s %8s %9s %9s %9s %9s %9s %9s %8s\n", "#", "equal%",
                    "<=1ulp%", "max ulp", "equal%", "<=1ulp%", "max ulp", "max abs", "dE mean",
                    "dE p99", "max abs", "dE mean", "dE p99", "gpu");
        std::string csv = "variant,glsl_equal_pct,glsl_within_1_ulp_pct,glsl_max_ulps,"
                          "hlsl_equal_pct,hlsl_within_1_ulp_pct,hlsl_max_ulps,"
                          "glsl_vs_full_max_abs,glsl_vs_full_de_mean,glsl_vs_full_de_p99,"
                          "hlsl_vs_full_max_abs,cpu_half_vs_full_max_abs,"
                          "cpu_half_vs_full_de_mean,cpu_half_vs_full_de_p99,gpu_nan_inf_pixels\n";
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        for (size_t i = 0; i < bench.rows.size(); ++i) {
            const HalfBenchRow& r = bench.rows[i];
            const HalfAgreement &g = r.vs_cpu_half[0], &h = r.vs_cpu_half[1];
            const uint64_t nan_inf = r.vs_full[0].nan_inf_pixels + r.vs_full[1].nan_inf_pixels;
            std::printf("%-4zu %8.2f %8.2f %8lld %8.2f %8.2f %8lld %9.3g %9.4f %9.4f %9.3g %9.4f "
                        "%9.4f %8llu\n",
                        i + 1, percent(g.equal, g.values), percent(g.within_1, g.values),
                        static_cast<long long>(g.max_ulps), percent(h.equal, h.values),
                        percent(h.within_1, h.values), static_cast<long long>(h.max_ulps),
                        r.vs_full[0].max_abs, r.vs_full[0].ciede2000_mean,
                        r.vs_full[0].ciede2000_p99, r.cpu_half_vs_full.max_abs,
                        r.cpu_half_vs_full.ciede2000_mean, r.cpu_half_vs_full.ciede2000_p99,
                        static_cast<unsigned long long>(nan_inf));
            csv += fmt::format(
                "\"{}\",{:.3f},{:.3f},{},{:.3f},{:.3f},{},{:.6g},{:.5f},{:.5f},"
                "{:.6g},{:.6g},{:.5f},{:.5f},{}\n",
                r.key, percent(g.equal, g.values), percent(g.within_1, g.values), g.max_ulps,
                percent(h.equal, h.values), percent(h.within_1, h.values), h.max_ulps,
                r.vs_full[0].max_abs, r.vs_full[0].ciede2000_mean, r.vs_full[0].ciede2000_p99,
                r.vs_full[1].max_abs, r.cpu_half_vs_full.max_abs, r.cpu_half_vs_full.ciede2000_mean,
                r.cpu_half_vs_full.ciede2000_p99, nan_inf);
            rows.push_back({{"variant", r.key},
                            {"glsl_vs_cpu_half", agreement_json(g, r.max_abs_vs_cpu_half[0])},
                            {"hlsl_vs_cpu_half", agreement_json(h, r.max_abs_vs_cpu_half[1])},
                            {"glsl_vs_full", error_json(r.vs_full[0])},
                            {"hlsl_vs_full", error_json(r.vs_full[1])},
                            {"cpu_half_vs_full", error_json(r.cpu_half_vs_full)}});
        }
        for (size_t i = 0; i < bench.rows.size(); ++i)
            std::printf("%zu: %s\n", i + 1, bench.rows[i].key.c_str());
        std::printf("%ux%u, synthetic scene, %s; values compared as binary16 (R, G, B); full "
                    "precision = the variant at precision=full on the GPU (GLSL)\n",
                    o->size, o->size, runner->device_info().name.c_str());
        nlohmann::ordered_json doc = {
            {"size", o->size}, {"device", runner->device_info().name}, {"rows", rows}};
        if (!write_bench_files(o->out, "half", csv, doc.dump(2) + "\n")) return kFailed;
        return kOk;
    };
}

} // namespace watergen::cli
