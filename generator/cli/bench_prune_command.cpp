// watergen bench prune: prints bench_prune() (render/prune_bench.h) as a table with the
// instructions per pixel of both shaders of each row counted under valgrind, and writes it to
// prune.csv and prune.json; fails when a pruned image differs by more than --tolerance.
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/eval/bench/prune_bench.h"
#include "watergen/pipeline/build_output.h"

namespace watergen::cli {

namespace {

struct Options {
    std::string material;
    std::vector<std::string> scenes;
    uint32_t size = 256, rounds = 20, draws = 3, cost_size = 64;
    size_t per_scene = 4;
    bool cost = true;
    double tolerance = 1e-4;
    std::string out = "out/bench";
    RunnerSetup runner;
};

std::string interval(const RatioInterval& r) {
    return fmt::format("{:.3f} [{:.3f}, {:.3f}]", r.ratio, r.lo, r.hi);
}

double ratio(double pruned, double unpruned) {
    return unpruned > 0 ? pruned / unpruned : 0;
}

// Instructions per pixel of both shaders of every row, scene by scene (pruned: folded under the
// scene's facts; unpruned: as composed; both drawn in the scene's conformed synthetic scene).
// The first scene's first unpruned shader is counted twice: the count's A/A. False on failure.
bool add_costs(const Options& o, const std::map<std::string, std::string>& scene_files,
               PruneBenchResult& result, double* cost_aa) {
    const double pixels = double(o.cost_size) * o.cost_size;
    for (size_t s = 0; s < result.scenes.size(); ++s) {
        PruneBenchScene& scene = result.scenes[s];
        std::vector<Variant> variants;
        for (const PruneBenchRow& row : scene.rows)
            variants.push_back(row.variant);
        if (variants.empty()) continue;
        std::vector<Variant> unpruned = variants;
        if (s == 0) unpruned.push_back(variants.front());
        std::string error;
        const auto pruned_counts = count_material_costs(o.material, scene_files.at(scene.name),
                                                        variants, o.cost_size, &error, true);
        const auto unpruned_counts =
            pruned_counts ? count_material_costs(o.material, scene_files.at(scene.name), unpruned,
                                                 o.cost_size, &error, false)
                          : std::nullopt;
        if (!unpruned_counts) {
            std::fprintf(stderr, "watergen: error: %s: instruction count: %s\n", scene.name.c_str(),
                         error.c_str());
            return false;
        }
        for (PruneBenchRow& row : scene.rows) {
            const std::string key = row.variant.key();
            row.cost_pruned = double(pruned_counts->at(key)) / pixels;
            row.cost_unpruned = double(unpruned_counts->at(key)) / pixels;
        }
        if (s == 0) {
            const std::string key = variants.front().key();
            *cost_aa =
                ratio(double(unpruned_counts->at(key + "#2")), double(unpruned_counts->at(key)));
        }
        summarise_prune_scene(scene);
    }
    return true;
}

void print_row(const PruneBenchRow& row) {
    const PruneMeasurement& r = row.measurement;
    std::printf("  %-44s %4zu->%-4zu %5zu->%-5zu %7.0f->%-7.0f %6.3f %24s %9.2g\n",
                row.short_key.substr(0, 44).c_str(), r.live_before, r.live_after,
                r.spirv_opt_unpruned, r.spirv_opt_pruned, row.cost_unpruned, row.cost_pruned,
                ratio(row.cost_pruned, row.cost_unpruned), interval(row.time).c_str(),
                row.max_diff);
}

std::string csv_row(const std::string& scene, const PruneBenchRow& row) {
    const PruneMeasurement& r = row.measurement;
    return fmt::format("{},\"{}\",{},{},{},{},{},{},{:.2f},{:.2f},{:.5f},{:.5f},{:.5f},{:.3g},"
                       "{:.3g},{:.3g}\n",
                       scene, row.variant.key(), r.live_before, r.live_after, r.spirv_unpruned,
                       r.spirv_pruned, r.spirv_opt_unpruned, r.spirv_opt_pruned, row.cost_unpruned,
                       row.cost_pruned, row.time.ratio, row.time.lo, row.time.hi, r.max_abs_glsl,
                       r.max_abs_hlsl, r.max_abs_cpu);
}

nlohmann::ordered_json json_row(const PruneBenchRow& row) {
    const PruneMeasurement& r = row.measurement;
    return {
        {"variant", row.variant.key()},
        {"ir_nodes", {r.live_before, r.live_after}},
        {"spirv", {r.spirv_unpruned, r.spirv_pruned}},
        {"spirv_opt", {r.spirv_opt_unpruned, r.spirv_opt_pruned}},
        {"instructions_per_pixel", {row.cost_unpruned, row.cost_pruned}},
        {"time_ratio", {{"ratio", row.time.ratio}, {"lo", row.time.lo}, {"hi", row.time.hi}}},
        {"max_abs", {{"glsl", r.max_abs_glsl}, {"hlsl", r.max_abs_hlsl}, {"cpu", r.max_abs_cpu}}}};
}

// Prints the table and fills the CSV and JSON forms of it.
void print_tables(const PruneBenchResult& result, std::string& csv,
                  nlohmann::ordered_json& scenes) {
    std::printf("  %-44s %10s %12s %16s %6s %24s %9s\n", "variant (the material's varying axes)",
                "IR nodes", "SPIR-V opt", "instr/px", "cost", "time [95% CI]", "max|diff|");
    csv = "scene,variant,ir_before,ir_after,spirv_unpruned,spirv_pruned,spirv_opt_unpruned,"
          "spirv_opt_pruned,instructions_per_pixel_unpruned,instructions_per_pixel_pruned,"
          "time_ratio,time_ratio_lo,time_ratio_hi,max_abs_glsl,max_abs_hlsl,max_abs_cpu\n";
    scenes = nlohmann::ordered_json::array();
    for (const PruneBenchScene& s : result.scenes) {
        std::printf("%s: %zu of %zu distinct shaders; %s\n", s.name.c_str(), s.rows.size(),
                    s.distinct, s.notes.c_str());
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        for (const PruneBenchRow& row : s.rows) {
            print_row(row);
            csv += csv_row(s.name, row);
            rows.push_back(json_row(row));
        }
        scenes.push_back({{"scene", s.name},
                          {"distinct_shaders", s.distinct},
                          {"notes", s.notes},
                          {"aa", {{"ratio", s.aa.ratio}, {"lo", s.aa.lo}, {"hi", s.aa.hi}}},
                          {"timing_trustworthy", s.timing_trustworthy()},
                          {"median_ratios",
                           {{"ir_nodes", s.ir},
                            {"spirv", s.spirv},
                            {"spirv_opt", s.spirv_opt},
                            {"instructions", s.cost},
                            {"time", s.time}}},
                          {"rows", rows}});
        if (!s.complete) break;
        if (s.rows.empty()) continue;
        std::printf("  median pruned/unpruned: IR nodes %.3f, SPIR-V %.3f, SPIR-V opt %.3f, "
                    "instructions %.3f, time %.3f; A/A time %s%s; max |diff| %.2g\n",
                    s.ir, s.spirv, s.spirv_opt, s.cost, s.time, interval(s.aa).c_str(),
                    s.timing_trustworthy() ? "" : " (outside +-3%: times not trustworthy)",
                    s.worst);
    }
}

} // namespace

Runner add_bench_prune_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<Options>();
    app.add_option("material", o->material, "material (default: the built-in default material)");
    app.add_option("--scene", o->scenes, "scene description (repeatable)")->required();
    app.add_option("--size", o->size, "image width and height in pixels (default 256)")
        ->check(CLI::Range(16, 4096));
    app.add_option("--rounds", o->rounds, "interleaved timing rounds per scene (default 20)")
        ->check(CLI::Range(2, 1000));
    add_instrument_options(app, o->draws, o->cost_size, o->cost);
    app.add_option("--variants", o->per_scene,
                   "distinct shaders measured per scene, chosen to cover the material's choices "
                   "first (default 4; 0: all)");
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
        PruneBenchResult result =
            bench_prune(*runner, m, plan->scenes, {o->size, o->rounds, o->draws, o->per_scene});
        std::map<std::string, std::string> scene_files; // scene name -> the file given
        for (size_t i = 0; i < scenes.size(); ++i)
            scene_files[scenes[i].name] = o->scenes[i];
        double cost_aa = 0;
        if (result.ok() && o->cost && !add_costs(*o, scene_files, result, &cost_aa)) return kFailed;

        std::string csv;
        nlohmann::ordered_json scenes_json;
        print_tables(result, csv, scenes_json);
        if (!result.ok()) {
            std::fprintf(stderr, "watergen: error: %s\n", result.error.c_str());
            return kFailed;
        }
        std::printf("ratios are pruned / unpruned (below 1: pruning saves). SPIR-V opt: fragment "
                    "instructions of the GLSL path after spirv-opt -O; instr/px: instructions "
                    "lavapipe executes per pixel for one %ux%u draw (valgrind)%s; time: steady "
                    "draw, %u rounds x %u draws interleaved at %ux%u on %s, median ratio "
                    "[95%% bootstrap CI]; max|diff| over the GLSL, HLSL and CPU images\n",
                    o->cost_size, o->cost_size,
                    o->cost ? fmt::format(", A/A {:.5f}", cost_aa).c_str() : " (not counted)",
                    o->rounds, o->draws, o->size, o->size, runner->device_info().name.c_str());
        const nlohmann::ordered_json doc = {
            {"size", o->size},      {"rounds", o->rounds},
            {"draws", o->draws},    {"cost_size", o->cost_size},
            {"cost_aa", cost_aa},   {"device", runner->device_info().name},
            {"scenes", scenes_json}};
        if (!write_bench_files(o->out, "prune", csv, doc.dump(2) + "\n")) return kFailed;
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
