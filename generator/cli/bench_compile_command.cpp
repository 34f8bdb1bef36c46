// Compile benchmark: the in-process chain against the same chain run through the
// command-line tools as processes, measured in the same run on the same shaders.
#include <cstdio>

#include "commands.h"
#include "watergen/eval/bench/compile_bench.h"

namespace watergen::cli {

Runner add_bench_compile_command(CLI::App& app, const Common& common) {
    struct Options {
        int repeat = 5;
        std::string out = "out/bench";
    };
    auto o = std::make_shared<Options>();
    app.add_option("--repeat", o->repeat,
                   "timed repetitions per variant and chain; the median is reported (default 5)")
        ->check(CLI::Range(1, 100));
    app.add_option("--out", o->out,
                   "directory for compile.csv and compile.json (default out/bench)");
    return [o, &common]() {
        const CompileBench bench = run_compile_bench(o->repeat);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        std::printf("%-46s %14s %14s %8s\n", "variant (4 shaders: GLSL+HLSL, vert+frag)",
                    "in-process ms", "processes ms", "ratio");
        for (const auto& r : bench.rows)
            std::printf("%-46s %14.2f %14.2f %7.1fx\n", r.key.c_str(), r.in_process_ms,
                        r.processes_ms, r.ratio());
        std::printf("%-46s %14.2f %14.2f %7.1fx\n", "median over variants",
                    bench.median_in_process_ms, bench.median_processes_ms, bench.median_ratio);
        std::printf("chain: glslang -> spirv-val -> spirv-opt -O -> spirv-val -> SPIRV-Cross (GLSL "
                    "330, ESSL 300, MSL) + round trip + reflection; median of %d runs\n",
                    o->repeat);
        if (!write_bench_files(o->out, "compile", bench.csv, bench.json)) return kFailed;
        return kOk;
    };
}

} // namespace watergen::cli
