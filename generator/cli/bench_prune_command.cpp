// watergen bench prune: prints bench_prune() (eval/bench/prune_bench.h) as a table with the
// instructions per pixel of both shaders of each row counted under valgrind, and writes it to
// prune.csv and prune.json; fails when a pruned image differs by more than --tolerance.
#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/bench/prune_bench.h"
#include "watergen/pipeline/build/build_output.h"

namespace watergen::cli {

namespace {

struct Options {
    std::vector<std::string> scenes;
    PruneBenchOptions bench;
    double tolerance = 1e-4;
    std::string out = "out/bench";
    RunnerSetup runner;
    std::vector<std::string> targets;
};

void print_row(const PruneBenchRow& row) {
    const PruneMeasurement& r = row.measurement;
    std::printf("  %-44s %4zu->%-4zu %5zu->%-5zu %7.0f->%-7.0f %6.3f %24s %9.2g\n",
                row.short_key.substr(0, 44).c_str(), r.live_before, r.live_after,
                r.spirv_opt_unpruned, r.spirv_opt_pruned, row.cost_unpruned, row.cost_pruned,
                row.cost_ratio(), interval_text(row.time).c_str(), row.max_diff);
}

void print_tables(const PruneBenchResult& result) {
    std::printf("  %-44s %10s %12s %16s %6s %24s %9s\n", "variant (the material's varying axes)",
                "IR nodes", "SPIR-V opt", "instr/px", "cost", "time [95% CI]", "max|diff|");
    for (const PruneBenchScene& s : result.scenes) {
        std::printf("%s: %zu of %zu distinct shaders; %s\n", s.name.c_str(), s.rows.size(),
                    s.distinct, s.notes.c_str());
        for (const PruneBenchRow& row : s.rows)
            print_row(row);
        if (!s.complete) break;
        if (s.rows.empty()) continue;
        std::printf("  median pruned/unpruned: IR nodes %.3f, SPIR-V %.3f, SPIR-V opt %.3f, "
                    "instructions %.3f, time %.3f; A/A time %s%s; max |diff| %.2g\n",
                    s.ir, s.spirv, s.spirv_opt, s.cost, s.time, interval_text(s.aa).c_str(),
                    s.timing_trustworthy() ? "" : " (outside +-3%: times not trustworthy)",
                    s.worst);
        for (const auto& [target, ratio] : s.target_cost) {
            std::printf("  %s (ACO fragment instr/px, unpruned->pruned):", target.c_str());
            for (const PruneBenchRow& row : s.rows)
                std::printf(" %.0f->%.0f", row.target_costs.at(target).first,
                            row.target_costs.at(target).second);
            std::printf("; median pruned/unpruned %.3f\n", ratio);
        }
    }
}

} // namespace

Runner add_bench_prune_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<Options>();
    PruneBenchOptions& b = o->bench;
    b.cost = true; // unless --no-cost
    app.add_option("material", b.material_path,
                   "material (default: the built-in default material)");
    app.add_option("--scene", o->scenes, "scene description (repeatable)")->required();
    app.add_option("--size", b.size, "image width and height in pixels (default 256)")
        ->check(CLI::Range(16, 4096));
    app.add_option("--rounds", b.rounds, "interleaved timing rounds per scene (default 20)")
        ->check(CLI::Range(2, 1000));
    add_instrument_options(app, b.draws, b.cost_size, b.cost);
    app.add_option("--variants", b.per_scene,
                   "distinct shaders measured per scene, chosen to cover the material's choices "
                   "first (default 4; 0: all)");
    app.add_option("--tolerance", o->tolerance,
                   "largest accepted image difference, pruned vs unpruned (default 1e-4)")
        ->check(finite_range(0.0, 1.0));
    app.add_option("--out", o->out, "directory for prune.csv and prune.json (default out/bench)");
    add_runner_options(app, o->runner);
    add_target_option(app, o->targets);
    return [o, &common]() {
        PruneBenchOptions& b = o->bench;
        const auto targets = resolve_targets(o->targets);
        if (!targets) return kUsage;
        b.cost = b.cost && has_lavapipe(*targets);
        b.gpu_targets = amd_targets(*targets);
        Material m;
        std::vector<SceneFacts> scenes;
        if (!load_material_and_scenes(b.material_path, o->scenes, m, scenes, common)) return kUsage;
        Diagnostics ds;
        auto plan = plan_build(m, scenes, ds);
        if (!plan) return stop(ds, "", RunStatus::BadInput, common);
        std::string cache_used;
        auto runner = create_runner(o->runner, &cache_used);
        if (!runner) return kNoDevice;
        for (size_t i = 0; i < scenes.size(); ++i)
            b.scene_files[scenes[i].name] = o->scenes[i];
        const PruneBenchResult result = bench_prune(*runner, m, plan->scenes, b);
        if (!result.cost_error.empty()) return stop(result.cost_error, RunStatus::Failed);
        print_tables(result);
        if (!result.ok()) return stop(result.error, RunStatus::Failed);
        std::printf("ratios are pruned / unpruned (below 1: pruning saves). SPIR-V opt: fragment "
                    "instructions of the GLSL path after spirv-opt -O; instr/px: instructions "
                    "lavapipe executes per pixel for one %ux%u draw (valgrind)%s; time: steady "
                    "draw, %u rounds x %u draws interleaved at %ux%u on %s, median ratio "
                    "[95%% bootstrap CI]; max|diff| over the GLSL, HLSL and CPU images\n",
                    b.cost_size, b.cost_size,
                    b.cost ? fmt::format(", A/A {:.5f}", result.cost_aa).c_str() : " (not counted)",
                    b.rounds, b.draws, b.size, b.size, runner->device_info().name.c_str());
        if (!write_bench_files(o->out, "prune", result.csv, result.json)) return kFailed;
        if (!result.within(o->tolerance)) {
            std::fprintf(
                stderr,
                "watergen: error: a pruned image differs from its unpruned one by more than %g\n",
                o->tolerance);
            return kFailed;
        }
        return kOk;
    };
}

} // namespace watergen::cli
