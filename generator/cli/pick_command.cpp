// `watergen pick`: per scene, the cheapest variant within an error budget (render/pick.h), its
// cost against the scene's gold, what each traded axis saved and cost in error, and a material
// file holding the picked choices. Costs come from a worker run under valgrind (--counted).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <valgrind/valgrind.h>

#include "commands.h"
#include "watergen/eval/compare/pick.h"
#include "watergen/eval/compare/prune_measure.h"
#include "watergen/eval/measure/draw_count.h"
#include "watergen/eval/scene/scene_views.h"
#include "watergen/pipeline/output_writer.h"

namespace watergen::cli {

namespace {

struct PickOptions {
    std::string material;
    std::vector<std::string> scenes, keys;
    std::vector<std::string> holds; // per axis, "" or a choice
    double max_de_p99 = 2.0, max_abs = INFINITY;
    uint32_t size = 256, cost_size = 64;
    std::string out = "out/pick";
    bool counted = false, unfolded = false;
    RunnerSetup runner;
};

// The worker: the given keys' shaders as the material builds them (for a scene: folded under
// its facts unless --unfolded, drawn in the scene's conformed synthetic scene either way), each
// GLSL path drawn with the count on; a key given twice is labelled "<key>#2".
int run_worker(const PickOptions& o, const Material& m, const ScenePlan* plan,
               const Common& common) {
    if (!RUNNING_ON_VALGRIND) {
        std::fprintf(stderr, "watergen: error: --counted is the worker of watergen pick and runs "
                             "under valgrind --tool=callgrind\n");
        return kUsage;
    }
    const SyntheticScene base = make_synthetic_scene(o.cost_size, o.cost_size);
    const SyntheticScene scene = plan ? conform_scene(base, *plan, m) : base;
    return draw_counted_keys(
        o.keys, scene,
        [&](const Variant& v) {
            return plan && !o.unfolded ? build_for_scene(m, *plan, v) : build_shader(m.compose(v));
        },
        common);
}

// Instructions per pixel of every candidate not counted yet, from one worker run; "" or the
// failure.
std::string count_costs(const PickOptions& o, const std::string& scene_path, PickPlan& pick) {
    std::vector<Variant> missing;
    for (const PickCandidate& c : pick.candidates)
        if (c.cost_per_pixel == 0) missing.push_back(c.variant);
    if (missing.empty()) return "";
    std::string error;
    const auto counts = count_material_costs(o.material, scene_path, missing, o.cost_size, &error);
    if (!counts) return error;
    const double pixels = double(o.cost_size) * o.cost_size;
    for (PickCandidate& c : pick.candidates)
        if (auto it = counts->find(c.variant.key()); it != counts->end())
            c.cost_per_pixel = double(it->second) / pixels;
    for (const PickCandidate& c : pick.candidates)
        if (c.cost_per_pixel == 0) return c.variant.key() + ": no instruction count";
    return "";
}

// The material file of the pick: the material with one choice per axis (its rules dropped).
nlohmann::ordered_json picked_material(const Material& m, const std::string& scene,
                                       const Variant& v, const PickBudget& budget) {
    nlohmann::ordered_json j;
    j["name"] = m.name + "-" + scene;
    j["description"] =
        "picked by watergen pick for scene " + scene +
        ": the cheapest variant with CIEDE2000 p99 <= " + std::to_string(budget.max_de_p99) +
        " against the scene's gold";
    if (!m.preset.empty()) j["preset"] = m.preset;
    const auto& list = axes();
    for (size_t a = 0; a < list.size(); ++a)
        j["axes"][list[a].name] = nlohmann::ordered_json::array({v.choices[a]});
    for (const auto& [name, p] : m.parameters) {
        if (p.value) j["parameters"][name]["value"] = *p.value;
        if (p.min) j["parameters"][name]["min"] = *p.min;
        if (p.max) j["parameters"][name]["max"] = *p.max;
    }
    for (Target t : m.targets)
        j["targets"].push_back(to_string(t));
    return j;
}

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
void print_pick(const PickPlan& pick, const PickCandidate& c) {
    const PickCandidate* gold = find_candidate(pick, pick.gold, "", "");
    std::printf("  picked: %s\n", c.variant.key().c_str());
    if (gold)
        std::printf("  cost %.3f x the gold's (%.1f vs %.1f instructions per pixel); dE00 p99 "
                    "%.3f, max abs %.3g\n",
                    c.cost_per_pixel / gold->cost_per_pixel, c.cost_per_pixel, gold->cost_per_pixel,
                    c.worst_de_p99, c.worst_max_abs);
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

} // namespace

std::optional<std::map<std::string, uint64_t>>
count_material_costs(const std::string& material_path, const std::string& scene_path,
                     const std::vector<Variant>& variants, uint32_t size, std::string* error,
                     bool folded) {
    std::vector<std::string> keys;
    for (const Variant& v : variants)
        keys.push_back(v.key());
    const KeyedWorker worker = [&](const std::vector<std::string>& part) {
        std::vector<std::string> argv = {std::filesystem::read_symlink("/proc/self/exe").string(),
                                         "pick", "--counted", "--cost-size", std::to_string(size)};
        // The worker runs in its scratch directory: paths as given would not resolve there.
        if (!scene_path.empty())
            argv.insert(argv.end(), {"--scene", std::filesystem::absolute(scene_path).string()});
        if (!folded) argv.push_back("--unfolded");
        if (!material_path.empty())
            argv.push_back(std::filesystem::absolute(material_path).string());
        for (const std::string& key : part)
            argv.insert(argv.end(), {"--key", key});
        return argv;
    };
    return count_keys_in_parallel(keys, worker, std::filesystem::temp_directory_path(),
                                  std::max(1u, std::thread::hardware_concurrency()), error);
}

Runner add_pick_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<PickOptions>();
    app.add_option("material", o->material, "material file (default: the built-in material)");
    app.add_option("--scene", o->scenes, "scene file (repeatable; at least one)");
    const auto& list = axes();
    o->holds.resize(list.size());
    for (size_t a = 0; a < list.size(); ++a)
        app.add_option("--" + list[a].name, o->holds[a],
                       "hold " + list[a].name +
                           " at this choice (axes of different models are "
                           "otherwise held at the richest reached choice)");
    app.add_option("--max-dE-p99", o->max_de_p99, "error budget: CIEDE2000 p99 (default 2)")
        ->check(finite_range(0, 100));
    app.add_option("--max-abs", o->max_abs, "error budget: max abs linear RGB (default none)")
        ->check(finite_range(0, 1e30));
    app.add_option("--size", o->size, "image size of the error measurement (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--cost-size", o->cost_size, "image size of the instruction count (default 64)")
        ->check(CLI::Range(8, 512));
    app.add_option("--out", o->out, "directory for <scene>.json material files (default out/pick)");
    app.add_flag("--counted", o->counted, "")->group("");   // the cost worker; hidden
    app.add_option("--key", o->keys, "")->group("");        // the worker's variants; hidden
    app.add_flag("--unfolded", o->unfolded, "")->group(""); // the worker draws them unpruned
    add_runner_options(app, o->runner);
    return [o, &common]() {
        Material m;
        std::vector<SceneFacts> scenes;
        if (!load_material_and_scenes(o->material, o->scenes, m, scenes, common)) return kUsage;
        std::map<std::string, std::string> hold;
        for (size_t a = 0; a < axes().size(); ++a)
            if (!o->holds[a].empty()) {
                Variant probe = default_variant();
                if (auto error = set_choice(probe, axes()[a].name, o->holds[a])) {
                    std::fprintf(stderr, "watergen: error: --%s: %s\n", axes()[a].name.c_str(),
                                 error->c_str());
                    return kUsage;
                }
                hold[axes()[a].name] = o->holds[a];
            }
        std::vector<ScenePlan> plans;
        for (const SceneFacts& s : scenes) {
            Diagnostics ds;
            auto plan = plan_scene(m, s, ds);
            print_diagnostics(ds, common);
            if (!plan) return kUsage;
            plans.push_back(std::move(*plan));
        }
        if (o->counted) return run_worker(*o, m, plans.empty() ? nullptr : &plans.front(), common);
        if (plans.empty()) {
            std::fprintf(stderr, "watergen: error: pick needs a scene: --scene FILE\n");
            return kUsage;
        }
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const PickBudget budget{o->max_de_p99, o->max_abs};
        for (size_t s = 0; s < plans.size(); ++s) {
            const ScenePlan& plan = plans[s];
            std::printf("%s\n", plan.scene.name.c_str());
            PickPlan pick = plan_pick(plan, hold);
            // Every view the scene may show, conformed.
            std::vector<std::pair<std::string, SyntheticScene>> views;
            for (const SceneView& view : scene_views()) {
                if (const std::string why = view_outside_scene(view, plan.scene); !why.empty()) {
                    std::printf("  view %s left out: %s\n", view.name.c_str(), why.c_str());
                    continue;
                }
                views.emplace_back(
                    view.name,
                    conform_scene(make_synthetic_scene(o->size, o->size, view), plan, m));
            }
            if (views.empty()) {
                std::fprintf(stderr, "watergen: error: %s: the scene shows none of the views\n",
                             plan.scene.name.c_str());
                return kUsage;
            }
            std::string error = measure_pick_errors(*runner, m, plan, views, pick);
            if (error.empty()) error = count_costs(*o, o->scenes[s], pick);
            const int chosen = error.empty() ? cheapest_within(pick.candidates, budget) : -1;
            if (chosen >= 0) { // what each axis saved: the pick with that axis at the gold's
                add_axis_alternatives(pick, pick.candidates[size_t(chosen)].variant);
                error = measure_pick_errors(*runner, m, plan, views, pick);
                if (error.empty()) error = count_costs(*o, o->scenes[s], pick);
            }
            if (!error.empty()) {
                std::fprintf(stderr, "watergen: error: %s: %s\n", plan.scene.name.c_str(),
                             error.c_str());
                return kFailed;
            }
            print_candidates(pick, budget);
            if (chosen < 0) {
                std::printf("  no reached variant within the budget\n");
                const PickCandidate* gold = find_candidate(pick, pick.gold, "", "");
                if (gold && !gold->reached && gold->within(budget))
                    std::printf("  the gold is within it: offer its choices in the material\n");
                continue;
            }
            print_pick(pick, pick.candidates[size_t(chosen)]);
            const auto path = std::filesystem::path(o->out) / (plan.scene.name + ".json");
            const std::string text =
                picked_material(m, plan.scene.name, pick.candidates[size_t(chosen)].variant, budget)
                    .dump(2) +
                "\n";
            std::error_code ec;
            std::filesystem::create_directories(path.parent_path(), ec);
            if (auto failure = write_file_atomically(path, text)) {
                std::fprintf(stderr, "watergen: error: %s\n", failure->c_str());
                return kFailed;
            }
            std::printf("  wrote %s\n", path.string().c_str());
        }
        return kOk;
    };
}

} // namespace watergen::cli
