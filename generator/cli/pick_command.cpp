// `watergen pick`: per scene, the cheapest variant within an error budget (pick_scene.h), its
// cost against the scene's gold, what each traded axis saved and cost in error, and a material
// file holding the picked choices. Costs come from a worker run under valgrind (--counted,
// cost_worker.h), or with --target from an AMD family's compiler (gpu_cost.h).
#include <cstdio>

#include "commands.h"
#include "watergen/eval/compare/pick_scene.h"
#include "watergen/eval/measure/cost_worker.h"

namespace watergen::cli {

namespace {

struct PickOptions {
    PickRequest request;
    std::vector<std::string> scenes, keys;
    std::vector<std::string> holds; // per axis, "" or a choice
    bool counted = false, unfolded = false;
    RunnerSetup runner;
    std::vector<std::string> targets;
};

void print_candidates(const PickPlan& pick, const PickBudget& budget) {
    std::printf("  gold: %s\n", pick.gold.key().c_str());
    for (const std::string& h : pick.held)
        std::printf("  held (different models, not traded): %s\n", h.c_str());
    std::printf("  %zu reached variants differ on a held axis or are other models (not traded); "
                "measured:\n",
                pick.other_looks);
    for (const PickCandidate& c : pick.candidates)
        std::printf("    %s%s\n      cost %8.1f/px  dE00 p99 %6.3f  max abs %9.3g  NaN %llu%s\n",
                    c.variant.key().c_str(), c.reached ? "" : " (not reached: for comparison)",
                    c.cost_per_pixel, c.worst_de_p99, c.worst_max_abs,
                    static_cast<unsigned long long>(c.nan_pixels),
                    c.within(budget) ? "" : "  (over budget)");
}

// The pick against the gold, and what each traded axis saved and cost in error.
void print_pick(const PickPlan& pick, const PickCandidate& c, const GpuTarget& target) {
    const PickCandidate* gold = find_candidate(pick, pick.gold, "", "");
    std::printf("  picked: %s\n", c.variant.key().c_str());
    if (gold)
        std::printf("  cost %.3f x the gold's (%.1f vs %.1f %s); dE00 p99 %.3f, max abs %.3g\n",
                    c.cost_per_pixel / gold->cost_per_pixel, c.cost_per_pixel, gold->cost_per_pixel,
                    cost_unit(target).c_str(), c.worst_de_p99, c.worst_max_abs);
    const auto& list = axes();
    for (size_t a = 0; a < list.size(); ++a) {
        if (c.variant.choices[a] == pick.gold.choices[a]) continue;
        const PickCandidate* alt =
            find_candidate(pick, c.variant, list[a].name, pick.gold.choices[a]);
        if (!alt) continue;
        std::printf("    %s=%s instead of %s: %+.1f%% cost, dE00 p99 %.3f -> %.3f\n",
                    list[a].name.c_str(), c.variant.choices[a].c_str(),
                    pick.gold.choices[a].c_str(),
                    100.0 * (c.cost_per_pixel / alt->cost_per_pixel - 1.0), alt->worst_de_p99,
                    c.worst_de_p99);
    }
}

// One scene's pick, printed; the exit code, kOk to go on with the next scene.
int pick_and_print(VulkanRunner& runner, const Material& m, const ScenePlan& plan,
                   const std::string& scene_path, const PickRequest& request) {
    std::printf("%s (cost: %s)\n", plan.scene.name.c_str(), cost_unit(request.target).c_str());
    const PickSceneRun run = pick_scene(runner, m, plan, scene_path, request);
    for (const std::string& note : run.notes)
        std::printf("  %s\n", note.c_str());
    if (!run.measured()) {
        std::fprintf(stderr, "watergen: error: %s: %s\n", plan.scene.name.c_str(),
                     run.error.c_str());
        return exit_code(run.status);
    }
    print_candidates(run.pick, request.budget);
    if (run.chosen < 0) {
        std::printf("  no reached variant within the budget\n");
        const PickCandidate* gold = find_candidate(run.pick, run.pick.gold, "", "");
        if (gold && !gold->reached && gold->within(request.budget))
            std::printf("  the gold is within it: offer its choices in the material\n");
        return kOk;
    }
    print_pick(run.pick, run.pick.candidates[size_t(run.chosen)], request.target);
    if (!run.write_error.empty()) {
        std::fprintf(stderr, "watergen: error: %s\n", run.write_error.c_str());
        return kFailed;
    }
    std::printf("  wrote %s\n", run.written.string().c_str());
    return kOk;
}

} // namespace

Runner add_pick_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<PickOptions>();
    PickRequest& r = o->request;
    app.add_option("material", r.material_path, "material file (default: the built-in material)");
    app.add_option("--scene", o->scenes, "scene file (repeatable; at least one)");
    const auto& list = axes();
    o->holds.resize(list.size());
    for (size_t a = 0; a < list.size(); ++a)
        app.add_option("--" + list[a].name, o->holds[a],
                       "hold " + list[a].name +
                           " at this choice (axes of different models are "
                           "otherwise held at the richest reached choice)");
    app.add_option("--max-dE-p99", r.budget.max_de_p99, "error budget: CIEDE2000 p99 (default 2)")
        ->check(finite_range(0, 100));
    app.add_option("--max-abs", r.budget.max_abs, "error budget: max abs linear RGB (default none)")
        ->check(finite_range(0, 1e30));
    app.add_option("--size", r.size, "image size of the error measurement (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--cost-size", r.cost_size, "image size of the instruction count (default 64)")
        ->check(CLI::Range(8, 512));
    app.add_option("--out", r.out, "directory for <scene>.json material files (default out/pick)");
    app.add_flag("--counted", o->counted, "")->group("");   // the cost worker; hidden
    app.add_option("--key", o->keys, "")->group("");        // the worker's variants; hidden
    app.add_flag("--unfolded", o->unfolded, "")->group(""); // the worker draws them unpruned
    add_runner_options(app, o->runner);
    add_target_option(app, o->targets);
    add_grid_options(app, r.grid);
    return [o, &common]() {
        PickRequest& r = o->request;
        const auto targets = resolve_targets(o->targets);
        if (!targets) return kUsage;
        if (targets->size() != 1) {
            std::fprintf(stderr, "watergen: error: --target: pick trades one target's cost; "
                                 "run it once per target\n");
            return kUsage;
        }
        r.target = targets->front();
        if (!check_grid(r.grid)) return kUsage;
        Material m;
        std::vector<SceneFacts> scenes;
        if (!load_material_and_scenes(r.material_path, o->scenes, m, scenes, common)) return kUsage;
        for (size_t a = 0; a < axes().size(); ++a)
            if (!o->holds[a].empty()) {
                Variant probe = default_variant();
                if (auto error = set_choice(probe, axes()[a].name, o->holds[a])) {
                    std::fprintf(stderr, "watergen: error: --%s: %s\n", axes()[a].name.c_str(),
                                 error->c_str());
                    return kUsage;
                }
                r.hold[axes()[a].name] = o->holds[a];
            }
        std::vector<ScenePlan> plans;
        for (const SceneFacts& s : scenes) {
            Diagnostics ds;
            auto plan = plan_scene(m, s, ds);
            print_diagnostics(ds, common);
            if (!plan) return kUsage;
            plans.push_back(std::move(*plan));
        }
        if (o->counted) {
            const MaterialCountJob job{r.material_path, o->scenes.empty() ? "" : o->scenes.front(),
                                       !o->unfolded,    r.cost_size,
                                       o->keys,         r.grid};
            const CountWorkerRun run =
                run_count_worker(job, m, plans.empty() ? nullptr : &plans.front());
            print_diagnostics(run.diagnostics, common);
            if (!run.error.empty())
                std::fprintf(stderr, "watergen: error: %s\n", run.error.c_str());
            return exit_code(run.status);
        }
        if (plans.empty()) {
            std::fprintf(stderr, "watergen: error: pick needs a scene: --scene FILE\n");
            return kUsage;
        }
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        for (size_t s = 0; s < plans.size(); ++s)
            if (const int code = pick_and_print(*runner, m, plans[s], o->scenes[s], r); code != kOk)
                return code;
        return kOk;
    };
}

} // namespace watergen::cli
