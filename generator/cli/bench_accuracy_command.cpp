// Accuracy bench: on every axis that has a gold choice, each cheaper choice against the gold,
// rendered in the same run: GPU time ratio and image error.
#include <cstdio>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/render/variant_render.h"

namespace watergen::cli {

namespace {

// The reference every row differs from in one axis: gold where an axis has one.
Variant reference_variant() {
    Variant v = default_variant();
    for (const auto& a : axes())
        for (const auto& c : a.choices)
            if (c.gold) set_choice(v, a.name, c.name);
    set_choice(v, "waves", "gerstner"); // analytic normals need a closed-form wave model
    return v;
}

struct Row {
    std::string axis, choice;
    bool gold = false;
    double steady_ms = 0, time_ratio = 0;
    size_t instructions = 0; // optimised fragment SPIR-V, GLSL path: a cost proxy free of timing noise
    ImageErrorStats error; // against the gold image of the same axis
    std::string note;
};

} // namespace

Runner add_bench_accuracy_command(CLI::App& app, const Common& common) {
    struct Options {
        uint32_t size = 256, draws = 15;
        std::string out = "out/bench";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 256)")->check(CLI::Range(16, 2048));
    app.add_option("--draws", o->draws, "timed draws per variant; the median is used (default 15)")->check(CLI::Range(3, 1000));
    app.add_option("--out", o->out, "directory for accuracy.csv and accuracy.json (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const SyntheticScene scene = make_synthetic_scene(o->size, o->size);
        const RenderSettings settings{o->size, o->size, o->draws, true};
        std::vector<Row> rows;
        for (const auto& axis : axes()) {
            const ChoiceInfo* gold = nullptr;
            for (const auto& c : axis.choices)
                if (c.gold) gold = &c;
            if (!gold) continue;
            Variant base = reference_variant();
            if (axis.name == "waves") set_choice(base, "normals", "detail_map"); // valid for every wave model
            std::vector<Row> axis_rows;
            VariantRender gold_render;
            std::optional<VariantBuild> gold_build;
            // Gold first, so every other row compares against it.
            std::vector<const ChoiceInfo*> order{gold};
            for (const auto& c : axis.choices)
                if (&c != gold) order.push_back(&c);
            for (const ChoiceInfo* c : order) {
                Variant v = base;
                set_choice(v, axis.name, c->name);
                Row row;
                row.axis = axis.name;
                row.choice = c->name;
                row.gold = c->gold;
                if (auto e = check_constraints(v)) {
                    row.note = "skipped: " + *e;
                    axis_rows.push_back(row);
                    continue;
                }
                const VariantBuild build = build_variant(v);
                if (!build.ok()) {
                    print_diagnostics(build.diagnostics, common);
                    return kFailed;
                }
                VariantRender r = render_variant(*runner, build, scene, settings);
                if (!r.ok()) {
                    std::fprintf(stderr, "watergen: error: %s: %s\n", v.key().c_str(), r.error.c_str());
                    return kFailed;
                }
                row.steady_ms = r.gpu[0].steady_draw_ms;
                row.instructions = build.languages[0].fragment.toolchain.instruction_count_optimized;
                if (c->gold) {
                    gold_render = std::move(r);
                    gold_build = build;
                    row.time_ratio = 1.0;
                    row.error = compare_images(gold_render.gpu_image[0], gold_render.gpu_image[0]);
                } else {
                    // The gold is timed again right after each candidate: this machine's speed
                    // drifts, and a ratio of back-to-back medians cancels most of that.
                    const VariantRender again = render_variant(*runner, *gold_build, scene, settings);
                    row.time_ratio = row.steady_ms / (again.ok() ? again.gpu[0].steady_draw_ms : gold_render.gpu[0].steady_draw_ms);
                    row.error = compare_images(r.gpu_image[0], gold_render.gpu_image[0]);
                }
                if (axis.name == "precision" && !c->gold) {
                    // lavapipe runs mediump at 32 bits: the GPU images agree. What half would
                    // cost is the CPU evaluator's half mode against double.
                    const EvalResult half = evaluate_image(build.shader.fragment, "color", scene.eval_inputs(),
                                                           o->size, o->size, EvalPrecision::Half);
                    row.error = compare_images(to_image(half, o->size, o->size), gold_render.cpu_double);
                    row.note = "error: CPU half evaluation vs double (lavapipe computes mediump in 32 bits)";
                }
                axis_rows.push_back(row);
            }
            rows.insert(rows.end(), axis_rows.begin(), axis_rows.end());
        }
        std::printf("%-11s %-33s %7s %10s %8s %11s %11s %9s %9s\n", "axis", "choice", "instrs", "steady ms", "time",
                    "max abs", "rmse", "dE mean", "dE p99");
        std::string csv = "axis,choice,gold,spirv_instructions,steady_ms,time_ratio,max_abs,rmse,ciede2000_mean,ciede2000_p99,note\n";
        nlohmann::ordered_json json = nlohmann::ordered_json::array();
        for (const auto& r : rows) {
            if (!r.note.empty() && r.steady_ms == 0) {
                std::printf("%-11s %-33s %s\n", r.axis.c_str(), r.choice.c_str(), r.note.c_str());
            } else {
                std::printf("%-11s %-33s %7zu %10.3f %7.2fx %11.3g %11.3g %9.3f %9.3f%s\n", r.axis.c_str(),
                            (r.choice + (r.gold ? " (gold)" : "")).c_str(), r.instructions, r.steady_ms, r.time_ratio, r.error.max_abs,
                            r.error.rmse, r.error.ciede2000_mean, r.error.ciede2000_p99, r.note.empty() ? "" : "  *");
            }
            csv += fmt::format("{},{},{},{},{:.4f},{:.3f},{:.6g},{:.6g},{:.4f},{:.4f},\"{}\"\n", r.axis, r.choice, r.gold,
                               r.instructions, r.steady_ms, r.time_ratio, r.error.max_abs, r.error.rmse, r.error.ciede2000_mean,
                               r.error.ciede2000_p99, r.note);
            json.push_back({{"axis", r.axis}, {"choice", r.choice}, {"gold", r.gold}, {"spirv_instructions", r.instructions},
                            {"steady_ms", r.steady_ms},
                            {"time_ratio", r.time_ratio}, {"max_abs", r.error.max_abs}, {"rmse", r.error.rmse},
                            {"ciede2000_mean", r.error.ciede2000_mean}, {"ciede2000_p99", r.error.ciede2000_p99},
                            {"note", r.note}});
        }
        std::printf("reference: %s\n%ux%u, median of %u timed draws, %s; Mesa shader cache %s\n",
                    reference_variant().key().c_str(), o->size, o->size, o->draws, runner->device_info().name.c_str(),
                    cache.c_str());
        const auto dir = std::filesystem::path(o->out);
        std::filesystem::create_directories(dir);
        nlohmann::ordered_json doc = {{"reference", reference_variant().key()}, {"size", o->size},
                                      {"draws", o->draws}, {"device", runner->device_info().name}, {"rows", json}};
        for (auto [name, text] : {std::pair{"accuracy.csv", csv}, std::pair{"accuracy.json", doc.dump(2) + "\n"}})
            if (auto e = write_file_atomically(dir / name, text)) {
                std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
                return kFailed;
            }
        std::printf("wrote %s and %s\n", (dir / "accuracy.csv").string().c_str(), (dir / "accuracy.json").string().c_str());
        return kOk;
    };
}

} // namespace watergen::cli
