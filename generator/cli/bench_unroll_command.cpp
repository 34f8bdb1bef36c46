// Unroll bench: prints run_unroll_bench() (eval/bench/unroll_bench.h), kept loops against
// unrolled ones on lavapipe per waves choice, and writes it to unroll.csv and unroll.json.
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/bench/unroll_bench.h"
#include "watergen/eval/measure/interleaved_timing.h" // median()

namespace watergen::cli {

namespace {

std::string range_text(const std::vector<double>& v) {
    if (v.empty()) return "-";
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return fmt::format("{:.2f} ({:.2f}-{:.2f})", median(v), *lo, *hi);
}

void print_table(const UnrollBench& b) {
    std::printf("unroll bench: %ux%u, %u rounds, each sample one language path of one render\n",
                b.size, b.size, b.rounds);
    std::printf("%-26s %11s %13s %9s %9s %22s %22s %9s %9s %22s %22s\n", "waves", "lines k/u",
                "instr k/u", "first k", "first u", "first u/k", "first A/A", "steady k", "steady u",
                "steady u/k", "steady A/A");
    for (const auto& r : b.rows)
        std::printf("%-26s %5zu/%-5zu %6zu/%-6zu %9.1f %9.1f %22s %22s %9.3f %9.3f %22s %22s\n",
                    r.waves.c_str(), r.kept.glsl_lines, r.unrolled.glsl_lines, r.kept.instructions,
                    r.unrolled.instructions, median(r.kept.first_draw_ms),
                    median(r.unrolled.first_draw_ms), range_text(r.first_draw_ratio).c_str(),
                    range_text(r.first_draw_aa).c_str(), median(r.kept.steady_draw_ms),
                    median(r.unrolled.steady_draw_ms), range_text(r.steady_ratio).c_str(),
                    range_text(r.steady_aa).c_str());
    std::printf("k: every loop [[dont_unroll]] / [loop]; u: every loop [[unroll]] / [unroll] "
                "(spirv-opt unrolls). Times in ms, medians; ratios: median (min-max) over "
                "rounds and paths; A/A: the kept shader against itself.\n");
    if (b.targets.empty()) return;
    std::printf("\nper family (ACO on RADV's null device, fragment stage, GLSL path; per-pixel: "
                "each kept loop weighted by its trip count):\n%-26s %-9s %9s %9s %11s %11s "
                "%9s %9s\n",
                "waves", "target", "instr k", "instr u", "per-pixel k", "per-pixel u", "VGPRs k",
                "VGPRs u");
    for (const std::string& t : b.targets)
        for (const auto& r : b.rows) {
            const StageGpuCost& k = r.kept.targets.at(t);
            const StageGpuCost& u = r.unrolled.targets.at(t);
            std::printf("%-26s %-9s %9.0f %9.0f %11.0f %11.0f %9.0f %9.0f\n", r.waves.c_str(),
                        t.c_str(), k.instructions, u.instructions,
                        k.per_pixel ? *k.per_pixel : k.instructions,
                        u.per_pixel ? *u.per_pixel : u.instructions, k.vgprs, u.vgprs);
        }
}

} // namespace

Runner add_bench_unroll_command(CLI::App& app, const Common& common) {
    struct Options {
        uint32_t size = 256, rounds = 3, draws = 5;
        std::string out = "out/bench";
        RunnerSetup runner;
        std::vector<std::string> targets;
    };
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--rounds", o->rounds, "interleaved rounds (default 3)")
        ->check(CLI::Range(1, 100));
    app.add_option("--draws", o->draws, "timed draws per render (default 5)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--out", o->out, "directory for unroll.csv and unroll.json (default out/bench)");
    add_runner_options(app, o->runner);
    app.add_option("--target", o->targets,
                   "AMD families whose compiler also builds both shaders of each waves choice "
                   "(repeatable or a comma list: " +
                       gpu_target_names() + ")")
        ->take_all();
    return [o, &common]() {
        const auto targets = resolve_targets(o->targets);
        if (!targets) return kUsage;
        const std::vector<GpuTarget> gpus = amd_targets(*targets);
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const UnrollBench bench = run_unroll_bench(*runner, o->size, o->rounds, o->draws, gpus);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        print_table(bench);
        return write_bench_files(o->out, "unroll", bench.csv, bench.json) ? kOk : kFailed;
    };
}

} // namespace watergen::cli
