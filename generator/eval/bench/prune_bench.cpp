#include "watergen/eval/bench/prune_bench.h"

#include <algorithm>
#include <set>

#include "watergen/eval/measure/draw_cost.h"
#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/eval/measure/interleaved_timing.h" // median()
#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/ir/emit/emitter.h"
#include "watergen/ir/fold/ir_fold.h"
#include "watergen/pipeline/build/build_output.h"

namespace watergen {

namespace {

// The axes the material varies.
std::vector<size_t> varying_axes(const Material& m) {
    std::vector<size_t> out;
    for (size_t a = 0; a < axes().size(); ++a)
        if (m.space.choices[a].size() > 1) out.push_back(a);
    return out;
}

std::string short_key(const Material& m, const Variant& v) {
    std::string key;
    for (size_t a : varying_axes(m))
        key += (key.empty() ? "" : ",") + v.choices[a];
    return key;
}

// A built shader's image on the CPU evaluator, in float.
std::optional<ImageRGBA32F> cpu_image(const VariantBuild& build, const SyntheticScene& scene,
                                      std::string* error) {
    const EvalResult r = evaluate_image(build.shader.fragment, "color", scene.eval_inputs(),
                                        scene.width, scene.height, EvalPrecision::Float);
    if (!r.ok()) {
        *error = "CPU evaluator: " + r.error;
        return std::nullopt;
    }
    return to_image(r, scene.width, scene.height);
}

// The image differences of one pair besides the GLSL one (from the timing run): the HLSL path
// drawn once each, and both graphs on the CPU.
std::string compare_other_paths(VulkanRunner& runner, const PrunePair& pair,
                                const SyntheticScene& scene, const RenderSettings& settings,
                                PruneMeasurement& m) {
    std::string error;
    ImageRGBA32F hlsl[2];
    const VariantBuild* builds[2] = {&pair.unpruned, &pair.pruned};
    for (int i = 0; i < 2; ++i) {
        const RenderResult r =
            runner.render(make_render_job(builds[i]->languages[1], scene, settings));
        if (!r.ok) return "HLSL path: " + r.error;
        hlsl[i] = ImageRGBA32F{settings.width, settings.height, r.rgba};
    }
    const auto h = pruned_difference(hlsl[1], hlsl[0], &error);
    if (!h) return error;
    m.max_abs_hlsl = *h;
    const auto cpu_unpruned = cpu_image(pair.unpruned, scene, &error);
    if (!cpu_unpruned) return error;
    const auto cpu_pruned = cpu_image(pair.pruned, scene, &error);
    if (!cpu_pruned) return error;
    const auto c = pruned_difference(*cpu_pruned, *cpu_unpruned, &error);
    if (!c) return error;
    m.max_abs_cpu = *c;
    return "";
}

// Measures one scene: sizes, interleaved times, images. "" or "key: why".
std::string measure_scene(VulkanRunner& runner, const Material& m, const ScenePlan& plan,
                          const std::vector<Variant>& variants, const SyntheticScene& scene,
                          const PruneBenchOptions& o, PruneBenchScene& out) {
    const RenderSettings settings{o.size, o.size, 1, false, false};
    std::vector<PrunePair> pairs;
    std::vector<RenderJob> jobs; // unpruned, pruned of each variant in turn (GLSL path)
    for (const Variant& v : variants) {
        PrunePair& pair = pairs.emplace_back(build_prune_pair(m, plan, v));
        if (!pair.ok()) return v.key() + ": " + pair.error;
        jobs.push_back(make_render_job(pair.unpruned.languages[0], scene, settings));
        jobs.push_back(make_render_job(pair.pruned.languages[0], scene, settings));
    }
    const InterleavedTiming timing = time_interleaved(runner, std::move(jobs), o.rounds, o.draws);
    if (!timing.ok()) return timing.error;
    out.aa = timing.aa;
    for (size_t i = 0; i < variants.size(); ++i) {
        PruneBenchRow row;
        row.variant = variants[i];
        row.short_key = short_key(m, variants[i]);
        row.measurement = pair_sizes(plan, variants[i], pairs[i]);
        const RenderResult& u = timing.results[2 * i];
        const RenderResult& p = timing.results[2 * i + 1];
        row.time =
            paired_ratio(round_medians(p.draw_ms, o.draws), round_medians(u.draw_ms, o.draws));
        std::string error;
        const auto g = pruned_difference(ImageRGBA32F{o.size, o.size, p.rgba},
                                         ImageRGBA32F{o.size, o.size, u.rgba}, &error);
        if (!g) return variants[i].key() + ": " + error;
        row.measurement.max_abs_glsl = *g;
        error = compare_other_paths(runner, pairs[i], scene, settings, row.measurement);
        if (!error.empty()) return variants[i].key() + ": " + error;
        const PruneMeasurement& r = row.measurement;
        row.max_diff = std::max({r.max_abs_glsl, r.max_abs_hlsl, r.max_abs_cpu});
        out.rows.push_back(std::move(row));
    }
    return "";
}

} // namespace

bool PruneBenchResult::within(double tolerance) const {
    for (const auto& s : scenes)
        for (const auto& row : s.rows)
            if (!(row.max_diff <= tolerance)) return false;
    return true;
}

std::vector<Variant> prune_bench_shaders(const Material& m, const ScenePlan& plan, size_t limit,
                                         size_t* distinct) {
    // One variant per distinct folded shader, in plan order.
    std::vector<Variant> shapes;
    std::set<std::string> seen;
    for (const Variant& v : plan.variants) {
        const WaterShader shader = m.compose(v);
        if (has_errors(shader.fragment.diagnostics())) continue;
        Diagnostics ignored;
        const FoldResult folded = fold_graph(shader.fragment, plan.facts);
        if (seen.insert(emit_fragment(folded.graph, Language::Glsl, "f", "", ignored).source)
                .second)
            shapes.push_back(v);
    }
    if (distinct) *distinct = shapes.size();
    if (limit == 0 || shapes.size() <= limit) return shapes;

    const std::vector<size_t> varying = varying_axes(m);
    std::set<std::pair<size_t, std::string>> covered;
    std::vector<bool> chosen(shapes.size(), false);
    for (size_t n = 0; n < limit; ++n) {
        size_t best = shapes.size(), best_gain = 0;
        for (size_t i = 0; i < shapes.size(); ++i) {
            if (chosen[i]) continue;
            size_t gain = 0;
            for (size_t a : varying)
                gain += !covered.count({a, shapes[i].choices[a]});
            if (best == shapes.size() || gain > best_gain) best = i, best_gain = gain;
        }
        chosen[best] = true;
        for (size_t a : varying)
            covered.insert({a, shapes[best].choices[a]});
    }
    std::vector<Variant> out;
    for (size_t i = 0; i < shapes.size(); ++i)
        if (chosen[i]) out.push_back(shapes[i]);
    return out;
}

void summarise_prune_scene(PruneBenchScene& s) {
    std::vector<double> ir, spirv, opt, time, cost;
    s.worst = 0;
    for (const auto& row : s.rows) {
        const PruneMeasurement& r = row.measurement;
        ir.push_back(double(r.live_after) / r.live_before);
        spirv.push_back(double(r.spirv_pruned) / r.spirv_unpruned);
        opt.push_back(double(r.spirv_opt_pruned) / r.spirv_opt_unpruned);
        time.push_back(row.time.ratio);
        if (row.cost_unpruned > 0) cost.push_back(row.cost_pruned / row.cost_unpruned);
        s.worst = std::max(s.worst, row.max_diff);
    }
    s.ir = median(ir);
    s.spirv = median(spirv);
    s.spirv_opt = median(opt);
    s.time = median(time);
    s.cost = cost.size() == s.rows.size() && !cost.empty() ? median(cost) : 0;
}

namespace {

double ratio(double pruned, double unpruned) {
    return unpruned > 0 ? pruned / unpruned : 0;
}

// Instructions per pixel of both shaders of every row, scene by scene. The first scene's first
// unpruned shader is counted twice: the count's A/A. "" or the failure.
std::string add_costs(const PruneBenchOptions& o, PruneBenchResult& result) {
    const double pixels = double(o.cost_size) * o.cost_size;
    for (size_t s = 0; s < result.scenes.size(); ++s) {
        PruneBenchScene& scene = result.scenes[s];
        std::vector<Variant> variants;
        for (const PruneBenchRow& row : scene.rows)
            variants.push_back(row.variant);
        if (variants.empty()) continue;
        std::vector<Variant> unpruned = variants;
        if (s == 0) unpruned.push_back(variants.front());
        const std::string& file = o.scene_files.at(scene.name);
        std::string error;
        const auto pruned_counts =
            count_material_costs(o.material_path, file, variants, o.cost_size, &error, true);
        const auto unpruned_counts =
            pruned_counts
                ? count_material_costs(o.material_path, file, unpruned, o.cost_size, &error, false)
                : std::nullopt;
        if (!unpruned_counts) return scene.name + ": instruction count: " + error;
        for (PruneBenchRow& row : scene.rows) {
            const std::string key = row.variant.key();
            row.cost_pruned = double(pruned_counts->at(key)) / pixels;
            row.cost_unpruned = double(unpruned_counts->at(key)) / pixels;
        }
        if (s == 0) {
            const std::string key = variants.front().key();
            result.cost_aa =
                ratio(double(unpruned_counts->at(key + "#2")), double(unpruned_counts->at(key)));
        }
        summarise_prune_scene(scene);
    }
    return "";
}

// Both shaders of every row on each AMD target, scene by scene; "" or the failure.
std::string add_gpu_costs(const PruneBenchOptions& o, const Material& m,
                          const std::vector<ScenePlan>& plans, PruneBenchResult& result) {
    for (size_t s = 0; s < result.scenes.size() && s < plans.size(); ++s) {
        PruneBenchScene& scene = result.scenes[s];
        std::vector<VariantBuild> builds; // per row: pruned, unpruned
        std::vector<std::string> names;
        for (const PruneBenchRow& row : scene.rows) {
            builds.push_back(build_for_scene(m, plans[s], row.variant));
            builds.push_back(build_shader(m.compose(row.variant)));
            names.push_back(row.variant.key() + " pruned");
            names.push_back(row.variant.key() + " unpruned");
        }
        if (builds.empty()) continue;
        const GlslFragmentCosts costs = glsl_fragment_costs(o.gpu_targets, builds, names);
        if (!costs.ok()) return scene.name + ": " + costs.error;
        for (size_t t = 0; t < o.gpu_targets.size(); ++t) {
            const std::string& target = o.gpu_targets[t].name;
            std::vector<double> ratios;
            for (size_t r = 0; r < scene.rows.size(); ++r) {
                const auto& pruned = costs.costs[t][2 * r];
                const auto& unpruned = costs.costs[t][2 * r + 1];
                if (!pruned || !unpruned)
                    return scene.name + ": " + target + ": " + names[2 * r] +
                           ": the family lacks a feature it needs";
                scene.rows[r].target_costs[target] = {*unpruned, *pruned};
                ratios.push_back(ratio(*pruned, *unpruned));
            }
            scene.target_cost[target] = median(ratios);
        }
    }
    return "";
}

PruneBenchResult measure_scenes(VulkanRunner& runner, const Material& m,
                                const std::vector<ScenePlan>& plans, const PruneBenchOptions& o) {
    PruneBenchResult out;
    const SyntheticScene base = make_synthetic_scene(o.size, o.size);
    for (const ScenePlan& sp : plans) {
        PruneBenchScene& s = out.scenes.emplace_back();
        s.name = sp.scene.name;
        const SyntheticScene scene = conform_scene(base, sp, m, &s.notes);
        const std::vector<Variant> variants = prune_bench_shaders(m, sp, o.per_scene, &s.distinct);
        if (variants.empty()) {
            s.complete = true;
            continue;
        }
        const std::string error = measure_scene(runner, m, sp, variants, scene, o, s);
        if (!error.empty()) {
            out.error = sp.scene.name + ": " + error;
            return out;
        }
        summarise_prune_scene(s);
        s.complete = true;
    }
    return out;
}

} // namespace

PruneBenchResult bench_prune(VulkanRunner& runner, const Material& m,
                             const std::vector<ScenePlan>& plans, const PruneBenchOptions& o) {
    PruneBenchResult out = measure_scenes(runner, m, plans, o);
    if (out.ok() && o.cost) out.cost_error = add_costs(o, out);
    if (out.ok() && out.cost_error.empty() && !o.gpu_targets.empty())
        out.cost_error = add_gpu_costs(o, m, plans, out);
    if (out.cost_error.empty()) add_prune_tables(o, runner.device_info().name, out);
    return out;
}

} // namespace watergen
