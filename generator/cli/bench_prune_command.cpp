// Pruning benchmark: per scene, each distinct folded shader against the same variant
// unpruned, rendered on the Vulkan runner over the synthetic scene conformed to the scene's
// facts: SPIR-V instruction counts, GPU time per draw, and how far the images differ.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/pipeline/build_output.h"
#include "watergen/ir/emitter.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/render/prune_measure.h"

namespace watergen::cli {

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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
    app.add_option("--size", o->size, "image width and height in pixels (default 256)")->check(CLI::Range(16, 4096));
    app.add_option("--draws", o->draws, "timed draws per render and language (default 21); the fastest of all is reported")
        ->check(CLI::Range(1, 1000));
    app.add_option("--rounds", o->rounds, "renders per shader, alternating pruned and unpruned (default 3)")
        ->check(CLI::Range(1, 100));
    app.add_option("--variants", o->per_scene, "at most this many distinct shaders per scene (default: all)");
    app.add_option("--tolerance", o->tolerance, "largest accepted image difference, pruned vs unpruned (default 1e-4)");
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
        const SyntheticScene base = make_synthetic_scene(o->size, o->size);
        const RenderSettings settings{o->size, o->size, o->draws, false};

        std::printf("%-14s %-58s %11s %11s %11s %9s %9s %10s\n", "scene", "variant (the material's varying axes)", "IR nodes", "SPIR-V", "SPIR-V opt",
                    "GPU glsl", "GPU hlsl", "max |diff|");
        std::string csv = "scene,variant,ir_before,ir_after,spirv_unpruned,spirv_pruned,spirv_opt_unpruned,spirv_opt_pruned,"
                          "gpu_ms_unpruned,gpu_ms_pruned,gpu_ms_unpruned_hlsl,gpu_ms_pruned_hlsl,max_abs_glsl,max_abs_hlsl,max_abs_cpu\n";
        nlohmann::ordered_json json = nlohmann::ordered_json::array();
        bool within = true;
        for (const ScenePlan& sp : plan->scenes) {
            std::string notes;
            const SyntheticScene scene = conform_scene(base, sp, m, &notes);
            std::printf("%s: %s\n", sp.scene.name.c_str(), notes.c_str());
            // One measurement per distinct folded shader.
            std::set<std::string> shapes;
            std::vector<double> r_spirv, r_opt, r_gpu, r_gpu_hlsl, r_ir;
            double worst = 0;
            for (const Variant& v : sp.variants) {
                if (o->per_scene && shapes.size() >= o->per_scene) break;
                const WaterShader shader = m.compose(v);
                if (has_errors(shader.fragment.diagnostics())) continue;
                Diagnostics ignored;
                const FoldResult folded = fold_graph(shader.fragment, sp.facts);
                if (!shapes.insert(emit_fragment(folded.graph, Language::Glsl, "f", "", ignored).source).second) continue;
                const PruneMeasurement r = measure_pruning(*runner, m, sp, v, scene, settings, o->rounds);
                if (!r.ok()) {
                    std::fprintf(stderr, "watergen: error: %s: %s: %s\n", sp.scene.name.c_str(), v.key().c_str(), r.error.c_str());
                    return kFailed;
                }
                const double diff = std::max({r.max_abs_glsl, r.max_abs_hlsl, r.max_abs_cpu});
                worst = std::max(worst, diff);
                within = within && diff <= o->tolerance;
                r_ir.push_back(double(r.live_after) / r.live_before);
                r_spirv.push_back(double(r.spirv_pruned) / r.spirv_unpruned);
                r_opt.push_back(double(r.spirv_opt_pruned) / r.spirv_opt_unpruned);
                r_gpu.push_back(r.gpu_ms_pruned / r.gpu_ms_unpruned);
                r_gpu_hlsl.push_back(r.gpu_ms_pruned_hlsl / r.gpu_ms_unpruned_hlsl);
                // The choices of the axes the material varies, without axis names (the CSV has keys).
                std::string shortkey;
                for (size_t a = 0; a < axes().size(); ++a)
                    if (m.space.choices[a].size() > 1) shortkey += (shortkey.empty() ? "" : ",") + v.choices[a];
                std::printf("%-14s %-58s %4zu->%-4zu %4zu->%-4zu %4zu->%-4zu %9.4f %9.4f %10.2g\n", sp.scene.name.c_str(),
                            shortkey.substr(0, 58).c_str(), r.live_before, r.live_after, r.spirv_unpruned, r.spirv_pruned,
                            r.spirv_opt_unpruned, r.spirv_opt_pruned, r.gpu_ms_pruned / r.gpu_ms_unpruned,
                            r.gpu_ms_pruned_hlsl / r.gpu_ms_unpruned_hlsl, diff);
                csv += fmt::format("{},\"{}\",{},{},{},{},{},{},{:.5f},{:.5f},{:.5f},{:.5f},{:.3g},{:.3g},{:.3g}\n", sp.scene.name,
                                   v.key(), r.live_before, r.live_after, r.spirv_unpruned, r.spirv_pruned, r.spirv_opt_unpruned,
                                   r.spirv_opt_pruned, r.gpu_ms_unpruned, r.gpu_ms_pruned, r.gpu_ms_unpruned_hlsl,
                                   r.gpu_ms_pruned_hlsl, r.max_abs_glsl, r.max_abs_hlsl, r.max_abs_cpu);
                json.push_back({{"scene", sp.scene.name}, {"variant", v.key()}, {"ir_nodes", {r.live_before, r.live_after}},
                                {"spirv", {r.spirv_unpruned, r.spirv_pruned}}, {"spirv_opt", {r.spirv_opt_unpruned, r.spirv_opt_pruned}},
                                {"gpu_ms_glsl", {r.gpu_ms_unpruned, r.gpu_ms_pruned}},
                                {"gpu_ms_hlsl", {r.gpu_ms_unpruned_hlsl, r.gpu_ms_pruned_hlsl}},
                                {"max_abs", {{"glsl", r.max_abs_glsl}, {"hlsl", r.max_abs_hlsl}, {"cpu", r.max_abs_cpu}}}});
            }
            std::printf("%-14s median ratio pruned/unpruned over %zu shaders: IR nodes %.3f, SPIR-V %.3f, SPIR-V opt %.3f, "
                        "GPU time %.3f (GLSL) %.3f (HLSL); max |diff| %.2g\n",
                        sp.scene.name.c_str(), r_spirv.size(), median(r_ir), median(r_spirv), median(r_opt), median(r_gpu),
                        median(r_gpu_hlsl), worst);
        }
        std::printf("ratios are pruned / unpruned (below 1: pruning saves); SPIR-V = fragment instructions of the GLSL path as "
                    "compiled and after spirv-opt -O; GPU = fastest of %u x %u timed draws at %ux%u on %s; max |diff| over the "
                    "GLSL, HLSL and CPU images\n",
                    o->rounds, o->draws, o->size, o->size, runner->device_info().name.c_str());
        std::filesystem::create_directories(o->out);
        const std::filesystem::path dir = o->out;
        for (auto [name, text] : {std::pair{"prune.csv", csv}, std::pair{"prune.json", json.dump(2) + "\n"}})
            if (auto e = write_file_atomically(dir / name, text)) {
                std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
                return kFailed;
            }
        std::printf("wrote %s and %s\n", (dir / "prune.csv").string().c_str(), (dir / "prune.json").string().c_str());
        if (!within) {
            std::fprintf(stderr, "watergen: error: a pruned image differs from its unpruned one by more than %g\n", o->tolerance);
            return kFailed;
        }
        return kOk;
    };
}

} // namespace watergen::cli
