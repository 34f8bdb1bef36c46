// watergen bench prune: prints bench_prune() (render/prune_bench.h) as a table and writes it
// to prune.csv and prune.json; fails when a pruned image differs by more than --tolerance.
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/pipeline/build_output.h"
#include "watergen/render/prune_bench.h"

namespace watergen::cli {

namespace {

void print_row(const std::string& scene, const PruneBenchRow& row) {
    const PruneMeasurement& r = row.measurement;
    std::printf("%-14s %-58s %4zu->%-4zu %4zu->%-4zu %4zu->%-4zu %9.4f %9.4f %10.2g\n",
                scene.c_str(), row.short_key.substr(0, 58).c_str(), r.live_before, r.live_after,
                r.spirv_unpruned, r.spirv_pruned, r.spirv_opt_unpruned, r.spirv_opt_pruned,
                r.gpu_ms_pruned / r.gpu_ms_unpruned, r.gpu_ms_pruned_hlsl / r.gpu_ms_unpruned_hlsl,
                row.max_diff);
}

std::string csv_row(const std::string& scene, const PruneBenchRow& row) {
    const PruneMeasurement& r = row.measurement;
    return fmt::format(
        "{},\"{}\",{},{},{},{},{},{},{:.5f},{:.5f},{:.5f},{:.5f},{:.3g},{:.3g},{:.3g}\n", scene,
        row.key, r.live_before, r.live_after, r.spirv_unpruned, r.spirv_pruned,
        r.spirv_opt_unpruned, r.spirv_opt_pruned, r.gpu_ms_unpruned, r.gpu_ms_pruned,
        r.gpu_ms_unpruned_hlsl, r.gpu_ms_pruned_hlsl, r.max_abs_glsl, r.max_abs_hlsl,
        r.max_abs_cpu);
}

nlohmann::ordered_json json_row(const std::string& scene, const PruneBenchRow& row) {
    const PruneMeasurement& r = row.measurement;
    return {
        {"scene", scene},
        {"variant", row.key},
        {"ir_nodes", {r.live_before, r.live_after}},
        {"spirv", {r.spirv_unpruned, r.spirv_pruned}},
        {"spirv_opt", {r.spirv_opt_unpruned, r.spirv_opt_pruned}},
        {"gpu_ms_glsl", {r.gpu_ms_unpruned, r.gpu_ms_pruned}},
        {"gpu_ms_hlsl", {r.gpu_ms_unpruned_hlsl, r.gpu_ms_pruned_hlsl}},
        {"max_abs", {{"glsl", r.max_abs_glsl}, {"hlsl", r.max_abs_hlsl}, {"cpu", r.max_abs_cpu}}}};
}

// Prints the table and fills the CSV and JSON forms of it.
void print_tables(const PruneBenchResult& result, std::string& csv, nlohmann::ordered_json& json) {
    std::printf("%-14s %-58s %11s %11s %11s %9s %9s %10s\n", "scene",
                "variant (the material's varying axes)", "IR nodes", "SPIR-V", "SPIR-V opt",
                "GPU glsl", "GPU hlsl", "max |diff|");
    csv = "scene,variant,ir_before,ir_after,spirv_unpruned,spirv_pruned,spirv_opt_"
          "unpruned,spirv_opt_pruned,"
          "gpu_ms_unpruned,gpu_ms_pruned,gpu_ms_unpruned_hlsl,gpu_ms_pruned_hlsl,"
          "max_abs_glsl,max_abs_hlsl,max_abs_cpu\n";
    json = nlohmann::ordered_json::array();
    for (const PruneBenchScene& s : result.scenes) {
        std::printf("%s: %s\n", s.name.c_str(), s.notes.c_str());
        for (const PruneBenchRow& row : s.rows) {
            print_row(s.name, row);
            csv += csv_row(s.name, row);
            json.push_back(json_row(s.name, row));
        }
        if (!s.complete) break;
        std::printf("%-14s median ratio pruned/unpruned over %zu shaders: IR nodes %.3f, "
                    "SPIR-V %.3f, SPIR-V opt %.3f, "
                    "GPU time %.3f (GLSL) %.3f (HLSL); max |diff| %.2g\n",
                    s.name.c_str(), s.rows.size(), s.ir, s.spirv, s.spirv_opt, s.gpu_glsl,
                    s.gpu_hlsl, s.worst);
    }
}

} // namespace

Runner add_bench_prune_command(CLI::App& app, const Common& common) {
    struct Options {
        std::string material;
        std::vector<std::string> scenes;
        uint32_t size = 256, draws = 21, rounds = 3;
        size_t per_scene = 0;
        double tolerance = 1e-4;
        std::string out = "out/bench";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    app.add_option("material", o->material, "material (default: the built-in default material)");
    app.add_option("--scene", o->scenes, "scene description (repeatable)")->required();
    app.add_option("--size", o->size, "image width and height in pixels (default 256)")
        ->check(CLI::Range(16, 4096));
    app.add_option(
           "--draws", o->draws,
           "timed draws per render and language (default 21); the fastest of all is reported")
        ->check(CLI::Range(1, 1000));
    app.add_option("--rounds", o->rounds,
                   "renders per shader, alternating pruned and unpruned (default 3)")
        ->check(CLI::Range(1, 100));
    app.add_option("--variants", o->per_scene,
                   "at most this many distinct shaders per scene (default: all)");
    app.add_option("--tolerance", o->tolerance,
                   "largest accepted image difference, pruned vs unpruned (default 1e-4)")
        ->check(finite_range(0.0, 1.0));
    app.add_option("--out", o->out, "directory for prune.csv and prune.json (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        Material m;
        std::vector<SceneFacts> scenes;
        if (!load_material_and_scenes(o->material, o->scenes, m, scenes, common)) return kUsage;
        Diagnostics ds;
        auto plan = plan_build(m, scenes, ds);
        if (!plan) {
            print_diagnostics(ds, common);
            return kUsage;
        }
        std::string cache_used;
        auto runner = create_runner(o->runner, &cache_used);
        if (!runner) return kNoDevice;
        const PruneBenchResult result =
            bench_prune(*runner, m, plan->scenes, {o->size, o->draws, o->rounds, o->per_scene});

        std::string csv;
        nlohmann::ordered_json json;
        print_tables(result, csv, json);
        if (!result.ok()) {
            std::fprintf(stderr, "watergen: error: %s\n", result.error.c_str());
            return kFailed;
        }
        std::printf("ratios are pruned / unpruned (below 1: pruning saves); SPIR-V = fragment "
                    "instructions of the GLSL path as "
                    "compiled and after spirv-opt -O; GPU = fastest of %u x %u timed draws at "
                    "%ux%u on %s; max |diff| over the "
                    "GLSL, HLSL and CPU images\n",
                    o->rounds, o->draws, o->size, o->size, runner->device_info().name.c_str());
        if (!write_bench_files(o->out, "prune", csv, json.dump(2) + "\n")) return kFailed;
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
