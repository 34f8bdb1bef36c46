// `watergen cost`: the instructions lavapipe executes for one draw of a variant, counted by
// valgrind (draw_cost.h; the command runs itself under valgrind as the worker: --counted,
// cost_worker.h), and with --target an AMD family's compiler statistics (gpu_cost.h).
#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "watergen/eval/measure/draw_cost.h"

namespace watergen::cli {

namespace {

struct CostOptions {
    VariantCountJob job; // the worker's keys: hidden --key
    uint32_t runs = 2;
    bool counted = false; // the worker, under valgrind
    std::string scratch;
    std::vector<std::string> targets;
};

} // namespace

Runner add_cost_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<CostOptions>();
    add_variant_options(app, o->job.variant, o->job.preset);
    app.add_option("--size", o->job.size, "image width and height (default 256)")
        ->check(CLI::Range(8, 2048));
    app.add_option("--runs", o->runs,
                   "valgrind runs; more than one shows the count repeats (default 2)")
        ->check(CLI::Range(1, 20));
    add_unroll_option(app, o->job.unroll);
    add_target_option(app, o->targets);
    add_view_option(app, o->job.view);
    add_grid_options(app, o->job.grid);
    const CLI::Option* tess_max = add_tess_max_option(app, o->job.tess_max);
    app.add_option("--scratch", o->scratch,
                   "directory under which each valgrind run keeps its dumps in a directory of "
                   "its own, removed afterwards (default: the system's temporary directory)");
    app.add_flag("--counted", o->counted, "")->group(""); // the worker; hidden
    app.add_option("--key", o->job.keys, "")->group("");  // the worker's variants; hidden
    app.add_flag("--strict-half", o->job.strict_half,
                 "count a half variant written in explicit 16-bit types (as render --strict-half "
                 "draws it) instead of with mediump / min16float hints");
    return [o, tess_max, &common]() {
        const Preset* preset = nullptr;
        if (!resolve_variant(o->job.variant, o->job.preset, &preset, common)) return kUsage;
        if (!check_grid(o->job.grid)) return kUsage;
        if (!o->counted) note_unused_tess_max(tess_max, o->job.variant);
        if (o->counted) {
            const CountWorkerRun run = run_count_worker(o->job);
            print_diagnostics(run.diagnostics, common);
            if (!run.error.empty())
                std::fprintf(stderr, "watergen: error: %s\n", run.error.c_str());
            return exit_code(run.status);
        }
        const auto targets = resolve_targets(o->targets);
        if (!targets) return kUsage;
        const std::filesystem::path scratch = o->scratch.empty()
                                                  ? std::filesystem::temp_directory_path()
                                                  : std::filesystem::path(o->scratch);
        const std::vector<GpuTarget> gpus = amd_targets(*targets);
        const bool lavapipe = has_lavapipe(*targets);
        if (!gpus.empty()) {
            const bool strict = o->job.strict_half && o->job.variant.choice("precision") == "half";
            const VariantBuild b =
                build_variant(o->job.variant, preset, EmitOptions{strict, {}, o->job.unroll});
            print_diagnostics(b.diagnostics, common);
            if (!b.ok()) return kFailed;
            const auto runs = variant_gpu_costs(gpus, {&b}, {"water"}, scratch, o->job.unroll);
            if (const int code = check_target_runs(runs); code != kOk) return code;
            std::printf("%s\n", o->job.variant.key().c_str());
            for (const auto& t : runs)
                print_gpu_costs(t);
            for (const auto& t : runs)
                for (const auto& c : t.costs)
                    if (!c.ok()) return kFailed;
            if (!lavapipe) return kOk;
        }
        const VariantCost cost = count_variant_cost(o->job, o->runs, scratch);
        if (!cost.ok()) {
            std::fprintf(stderr, "watergen: error: %s\n", cost.error.c_str());
            return kFailed;
        }
        std::printf("%s\ninstructions lavapipe executes (valgrind callgrind), %u run(s): one "
                    "%ux%u draw in view %s, and pipeline creation through the first draw (the "
                    "JIT):\n",
                    o->job.variant.key().c_str(), o->runs, o->job.size, o->job.size,
                    o->job.view.c_str());
        const double pixels = double(o->job.size) * o->job.size;
        for (size_t i = 0; i < 2; ++i) {
            const char* path = i == 0 ? "glsl" : "hlsl";
            const auto& c = cost.paths[i];
            if (!c) {
                std::fprintf(stderr, "watergen: error: valgrind gave no count of the %s path\n",
                             path);
                return kFailed;
            }
            std::printf("  %-5s %14llu  %9.1f per pixel  runs differ by %.4f%%   first draw "
                        "%14llu  runs differ by %.4f%%\n",
                        path, static_cast<unsigned long long>(c->draw),
                        static_cast<double>(c->draw) / pixels, c->draw_spread,
                        static_cast<unsigned long long>(c->first), c->first_spread);
        }
        return kOk;
    };
}

} // namespace watergen::cli
