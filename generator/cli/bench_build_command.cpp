// watergen bench build: prints bench_build() (pipeline/build_bench.h) as a table and writes
// it to build.csv and build.json.
#include <cstdio>

#include "commands.h"
#include "watergen/eval/bench/build_bench.h"
#include "watergen/pipeline/jobs/parallel_build.h"

namespace watergen::cli {

Runner add_bench_build_command(CLI::App& app, const Common& common) {
    struct Options {
        std::string material;
        std::vector<std::string> scenes;
        std::string out = "out/bench";
        unsigned threads = 0;
        size_t sample = 48;
    };
    auto o = std::make_shared<Options>();
    app.add_option("material", o->material,
                   "material of the pruned example (default: the built-in default material)");
    app.add_option("--scene", o->scenes, "scenes of the pruned example (repeatable)");
    add_jobs_option(app, o->threads,
                    "threads of the 'all threads' runs (default: every hardware thread)");
    app.add_option("--sample", o->sample,
                   "full-space variants to build, evenly spaced (default 48)")
        ->check(CLI::Validator(
            [](std::string& in) { return CLI::Range(size_t{1}, count_variants(full_space()))(in); },
            "INT in [1 - the full space's size]"));
    app.add_option("--out", o->out, "directory for build.csv and build.json (default out/bench)");
    return [o, &common]() {
        BuildBenchRequest request;
        if (!load_material_and_scenes(o->material, o->scenes, request.example, request.scenes,
                                      common))
            return kUsage;
        request.threads = o->threads ? capped_jobs(o->threads) : 0;
        request.sample = o->sample;
        const BuildBenchResult result = bench_build(request);
        if (!result.ok()) {
            print_diagnostics(result.diagnostics, common);
            return kFailed;
        }
        std::printf("%-78s %9s %9s %12s  %s\n", "what", "variants", "seconds", "variants/s", "");
        for (const auto& r : result.rows)
            std::printf("%-78s %9zu %9.3f %12.1f  %s\n", r.what.c_str(), r.variants, r.seconds,
                        r.rate(), r.note.c_str());
        std::printf("cold: empty cache, every distinct shader through glslang (GLSL + HLSL), "
                    "spirv-val, spirv-opt, SPIRV-Cross "
                    "and reflection; warm: the same build again (every variant from the cache); "
                    "no-op: again with the build record (nothing changed: the output's sizes and "
                    "hashes verified, no IR work); %u hardware threads\n",
                    hardware_threads());
        if (!write_bench_files(o->out, "build", result.csv, result.json)) return kFailed;
        return kOk;
    };
}

} // namespace watergen::cli
