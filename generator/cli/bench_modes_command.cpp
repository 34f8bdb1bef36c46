// watergen bench modes [MATERIAL]: prints bench_modes() (eval/bench/modes_bench.h) as a table and
// writes it to modes.csv and modes.json; fails when a mode's image differs from the
// permutation's by more than --tolerance.
#include <cstdio>

#include "commands.h"
#include "watergen/eval/bench/modes_bench.h"
#include "watergen/pipeline/output/output_writer.h"

namespace watergen::cli {

namespace {

void print_table(const ModesBenchResult& r) {
    std::printf("%-19s %7s %12s %11s %11s %12s %10s %11s %10s %10s\n", "mode", "shaders",
                "gen+compile", "per variant", "SPIR-V KiB", "per draw KiB", "pipeline",
                "first draw", "steady", "max |diff|");
    const double n = static_cast<double>(r.material_variants);
    for (const ModeRow& row : r.rows)
        std::printf("%-19s %7zu %10.0f ms %8.2f ms %11.1f %12.1f %8.2f ms %8.1f ms %7.2f ms "
                    "%10.2g\n",
                    row.mode.c_str(), row.shaders, row.generate_compile_ms,
                    row.generate_compile_ms / n, row.spirv_bytes / 1024,
                    row.spirv_bytes_per_draw / 1024, row.pipeline_ms, row.first_draw_ms,
                    row.steady_ms, row.max_abs);
}

// Per mode and AMD family: what its pipelines cost the GPU (register pressure sets occupancy:
// the waves a SIMD keeps in flight to hide latency).
void print_target_table(const ModesBenchResult& r) {
    std::printf("\nper family (ACO on RADV's null device, fragment stage, GLSL path; medians over "
                "the rendered variants, and the worst):\n%-19s %-9s %7s %9s %6s %8s %6s %6s "
                "%10s %8s %6s\n",
                "mode", "target", "instr", "per-pixel", "VGPRs", "VGPR max", "SGPRs", "waves",
                "waves min", "code KiB", "spills");
    for (const std::string& t : r.targets)
        for (const ModeRow& row : r.rows) {
            const ModeTargetCost& c = row.targets.at(t);
            std::printf("%-19s %-9s %7.0f %9.0f %6.0f %8.0f %6.0f %6.0f %10.0f %8.2f %6.0f\n",
                        row.mode.c_str(), t.c_str(), c.instructions, c.per_pixel, c.vgprs,
                        c.vgprs_max, c.sgprs, c.waves_per_simd, c.waves_min, c.code_bytes / 1024,
                        c.spills);
        }
}

} // namespace

Runner add_bench_modes_command(CLI::App& app, const Common& common) {
    struct Options {
        std::string material;
        ModesBenchOptions bench;
        double tolerance = 1e-6;
        std::string out = "out/bench";
        RunnerSetup runner;
        std::vector<std::string> targets;
    };
    auto o = std::make_shared<Options>();
    app.add_option("material", o->material, "material (default: the built-in default material)");
    app.add_option("--size", o->bench.size, "image width and height in pixels (default 256)")
        ->check(CLI::Range(16, 4096));
    app.add_option("--variants", o->bench.variants,
                   "variants rendered, spread over the material's (default 6; 0: every one)");
    app.add_option("--rounds", o->bench.rounds,
                   "renders per variant and mode, the modes interleaved (default 3)")
        ->check(CLI::Range(1, 100));
    app.add_option("--draws", o->bench.draws, "timed draws per render (default 5)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--tolerance", o->tolerance,
                   "largest accepted image difference from the permutation (default 1e-6)")
        ->check(finite_range(0.0, 1.0));
    app.add_option("--out", o->out, "directory for modes.csv and modes.json (default out/bench)");
    add_runner_options(app, o->runner);
    app.add_option("--target", o->targets,
                   "AMD families whose compiler also builds each rendered variant in each mode "
                   "(repeatable or a comma list: " +
                       gpu_target_names() +
                       "): VGPRs, occupancy, code size per mode and family in the table and "
                       "modes_targets.csv")
        ->take_all();
    return [o, &common]() {
        const auto targets = resolve_targets(o->targets);
        if (!targets) return kUsage;
        o->bench.gpu_targets = amd_targets(*targets);
        Material m;
        std::vector<SceneFacts> none;
        if (!load_material_and_scenes(o->material, {}, m, none, common)) return kUsage;
        std::string cache_used;
        auto runner = create_runner(o->runner, &cache_used);
        if (!runner) return kNoDevice;
        const ModesBenchResult r = bench_modes(*runner, m, o->bench);
        if (!bench_succeeded({}, r.error, common)) return kFailed;
        print_table(r);
        std::printf("material %s (%zu variants) on %s, %ux%u, shader cache %s; gen+compile: every "
                    "shader of the mode, one thread (frozen: plus freezing every variant); "
                    "SPIR-V: fragment, GLSL path, optimised; pipeline / first draw (JIT) / "
                    "steady: medians of %u rounds over the rendered variants; max |diff|: "
                    "against the permutation's image, GLSL and HLSL paths\n",
                    r.material.c_str(), r.material_variants, r.device.c_str(), o->bench.size,
                    o->bench.size, cache_used.c_str(), o->bench.rounds);
        if (!r.targets.empty()) print_target_table(r);
        if (!write_bench_files(o->out, "modes", r.csv, r.json)) return kFailed;
        if (!r.targets_csv.empty()) {
            const auto file = std::filesystem::path(o->out) / "modes_targets.csv";
            if (auto e = write_file_atomically(file, r.targets_csv)) {
                std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
                return kFailed;
            }
            std::printf("wrote %s\n", file.string().c_str());
        }
        if (const ModeRow* row = r.beyond(o->tolerance)) {
            std::fprintf(stderr,
                         "watergen: error: %s draws images %g from the permutation's "
                         "(tolerance %g)\n",
                         row->mode.c_str(), row->max_abs, o->tolerance);
            return kFailed;
        }
        return kOk;
    };
}

} // namespace watergen::cli
