#include "watergen/eval/compare/pick_scene.h"

#include <nlohmann/json.hpp>

#include "watergen/eval/measure/draw_cost.h"
#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/eval/scene/scene_conform.h"
#include "watergen/pipeline/output/output_writer.h"

namespace watergen {

namespace {

// The target's fragment instructions per pixel (ACO, loops weighted) of each variant as the
// build for the scene ships it, by key; nullopt and *error (and *no_device) when a run failed
// or the family cannot run a variant.
std::optional<std::map<std::string, double>> aco_costs(const GpuTarget& target, const Material& m,
                                                       const ScenePlan& plan,
                                                       const std::vector<Variant>& variants,
                                                       std::string* error, bool* no_device) {
    std::vector<VariantBuild> builds;
    std::vector<std::string> keys;
    for (const Variant& v : variants) {
        builds.push_back(build_for_scene(m, plan, v));
        if (!builds.back().ok()) {
            *error = v.key() + ": the variant does not build";
            return std::nullopt;
        }
        keys.push_back(v.key());
    }
    const GlslFragmentCosts costs = glsl_fragment_costs({target}, builds, keys);
    *no_device = costs.no_device;
    if (!costs.ok()) {
        *error = costs.error;
        return std::nullopt;
    }
    std::map<std::string, double> out;
    for (size_t i = 0; i < keys.size(); ++i) {
        if (!costs.costs[0][i]) {
            *error = target.name + ": " + keys[i] + ": the family lacks a feature it needs";
            return std::nullopt;
        }
        out[keys[i]] = *costs.costs[0][i];
    }
    return out;
}

// The cost per pixel of every candidate not costed yet, from one worker run; "" or the
// failure.
std::string count_costs(const PickRequest& request, const Material& m, const ScenePlan& plan,
                        const std::string& scene_path, PickPlan& pick, bool* no_device) {
    std::vector<Variant> missing;
    for (const PickCandidate& c : pick.candidates)
        if (c.cost_per_pixel == 0) missing.push_back(c.variant);
    if (missing.empty()) return "";
    std::string error;
    if (!request.target.is_lavapipe()) {
        const auto costs = aco_costs(request.target, m, plan, missing, &error, no_device);
        if (!costs) return error;
        for (PickCandidate& c : pick.candidates)
            if (auto it = costs->find(c.variant.key()); it != costs->end())
                c.cost_per_pixel = it->second;
        return "";
    }
    const auto counts = count_material_costs(request.material_path, scene_path, missing,
                                             request.cost_size, &error, true, request.grid);
    if (!counts) return error;
    const double pixels = double(request.cost_size) * request.cost_size;
    for (PickCandidate& c : pick.candidates)
        if (auto it = counts->find(c.variant.key()); it != counts->end())
            c.cost_per_pixel = double(it->second) / pixels;
    for (const PickCandidate& c : pick.candidates)
        if (c.cost_per_pixel == 0) return c.variant.key() + ": no instruction count";
    return "";
}

// The material file of the pick: the material with one choice per axis (its rules dropped).
nlohmann::ordered_json picked_material(const Material& m, const std::string& scene,
                                       const Variant& v, const PickBudget& budget,
                                       const GpuTarget& target) {
    nlohmann::ordered_json j;
    j["name"] = m.name + "-" + scene;
    j["description"] = "picked by watergen pick for scene " + scene + ": the cheapest variant on " +
                       target.name + " with CIEDE2000 p99 <= " + std::to_string(budget.max_de_p99) +
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

} // namespace

PickSceneRun pick_scene(VulkanRunner& runner, const Material& m, const ScenePlan& plan,
                        const std::string& scene_path, const PickRequest& request) {
    PickSceneRun run;
    run.pick = plan_pick(plan, request.hold);
    // Every view the scene may show, conformed.
    std::vector<std::pair<std::string, SyntheticScene>> views;
    for (const SceneView& view : scene_views()) {
        if (const std::string why = view_outside_scene(view, plan.scene); !why.empty()) {
            run.notes.push_back("view " + view.name + " left out: " + why);
            continue;
        }
        views.emplace_back(
            view.name,
            conform_scene(make_synthetic_scene(request.size, request.size, view), plan, m));
    }
    if (views.empty()) {
        run.error = "the scene shows none of the views";
        run.status = RunStatus::BadInput;
        return run;
    }
    PickPlan& pick = run.pick;
    bool no_device = false;
    std::string error = measure_pick_errors(runner, m, plan, views, pick, request.grid);
    if (error.empty()) error = count_costs(request, m, plan, scene_path, pick, &no_device);
    run.chosen = error.empty() ? cheapest_within(pick.candidates, request.budget) : -1;
    if (run.chosen >= 0) { // what each axis saved: the pick with that axis at the gold's
        add_axis_alternatives(pick, pick.candidates[size_t(run.chosen)].variant);
        error = measure_pick_errors(runner, m, plan, views, pick, request.grid);
        if (error.empty()) error = count_costs(request, m, plan, scene_path, pick, &no_device);
    }
    if (!error.empty()) {
        run.error = error;
        run.status = no_device ? RunStatus::NoDevice : RunStatus::Failed;
        return run;
    }
    if (run.chosen < 0) return run;
    const auto path = request.out / (plan.scene.name + ".json");
    const std::string text =
        picked_material(m, plan.scene.name, pick.candidates[size_t(run.chosen)].variant,
                        request.budget, request.target)
            .dump(2) +
        "\n";
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (auto failure = write_file_atomically(path, text)) {
        run.write_error = *failure;
        run.status = RunStatus::Failed;
        return run;
    }
    run.written = path;
    return run;
}

} // namespace watergen
