#include "watergen/eval/bench/accuracy_bench.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/eval/measure/draw_cost.h"
#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/plan/variant_space.h"

namespace watergen {

Variant accuracy_reference_variant() {
    Variant v = default_variant();
    for (const auto& a : axes())
        for (const auto& c : a.choices)
            if (c.gold) set_choice(v, a.name, c.name);
    set_choice(v, "waves", "gerstner"); // analytic normals need a closed-form wave model
    return v;
}

namespace {

// The worst of each figure over the views, and the view of the worst p99 dE00.
void take_worst(const std::vector<ComparedView>& views, const std::vector<std::string>& names,
                AccuracyRow& row) {
    for (size_t i = 0; i < views.size(); ++i) {
        const ImageErrorStats& e = views[i].error;
        if (i == 0 || e.ciede2000_p99 > row.worst.ciede2000_p99) {
            row.worst.ciede2000_p99 = e.ciede2000_p99;
            row.worst_view = names[i];
        }
        row.worst.max_abs = std::max(row.worst.max_abs, e.max_abs);
        row.worst.rmse = std::max(row.worst.rmse, e.rmse);
        row.worst.ciede2000_mean = std::max(row.worst.ciede2000_mean, e.ciede2000_mean);
        row.worst.nan_inf_where_reference_finite += e.nan_inf_where_reference_finite;
    }
}

// One axis: its gold against every other valid choice; false at the first failure.
bool measure_axis(VulkanRunner& runner, const AxisInfo& axis, const ChoiceInfo& gold,
                  const std::vector<std::pair<std::string, SyntheticScene>>& views, uint32_t rounds,
                  uint32_t draws, AccuracyBench& out) {
    Variant base = accuracy_reference_variant();
    if (axis.name == "waves") set_choice(base, "normals", "detail_map"); // valid for every model
    CompareRequest request;
    request.views = views;
    request.rounds = rounds;
    request.draws = draws;
    request.both_paths = false;
    request.reference = base;
    set_choice(*request.reference, axis.name, gold.name);
    // A half row renders in 16-bit arithmetic (strict half): lavapipe runs mediump at 32.
    request.build = [](const Variant& v) {
        return build_variant(v, nullptr, EmitOptions{v.choice("precision") == "half"});
    };
    std::vector<AccuracyRow> skipped;
    for (const ChoiceInfo& c : axis.choices) {
        Variant v = base;
        set_choice(v, axis.name, c.name);
        if (auto e = check_constraints(v)) {
            AccuracyRow row;
            row.axis = axis.name;
            row.choice = c.name;
            row.variant = v;
            row.note = "skipped: " + *e;
            skipped.push_back(row);
            continue;
        }
        request.variants.push_back(v);
    }
    const CompareRun run = run_compare(runner, request);
    if (!run.ok()) {
        out.diagnostics = run.diagnostics;
        out.error = run.error;
        return false;
    }
    out.axes.push_back({axis.name, run.reference, run.aa});
    for (const CompareEntry& e : run.entries) {
        AccuracyRow row;
        row.axis = axis.name;
        row.choice = e.variant.choice(axis.name);
        row.variant = e.variant;
        row.gold = row.choice == gold.name;
        row.relation = e.relation;
        row.time = e.time;
        row.spirv_instructions = e.spirv_instructions;
        take_worst(e.views, out.views, row);
        if (row.choice == "half") row.note = "strict half: 16-bit arithmetic on the GPU";
        out.rows.push_back(row);
    }
    out.rows.insert(out.rows.end(), skipped.begin(), skipped.end());
    return true;
}

} // namespace

AccuracyBench run_accuracy_bench(VulkanRunner& runner,
                                 const std::vector<std::pair<std::string, SyntheticScene>>& views,
                                 uint32_t rounds, uint32_t draws) {
    AccuracyBench bench;
    for (const auto& [name, scene] : views)
        bench.views.push_back(name);
    for (const auto& axis : axes()) {
        const ChoiceInfo* gold = nullptr;
        for (const auto& c : axis.choices)
            if (c.gold) gold = &c;
        if (gold && !measure_axis(runner, axis, *gold, views, rounds, draws, bench)) break;
    }
    return bench;
}

double AccuracyBench::gold_cost(const std::string& axis) const {
    for (const AccuracyRow& r : rows)
        if (r.axis == axis && r.gold) return r.cost_per_pixel;
    return 0;
}

namespace {

double cost_on(const AccuracyRow& r, const std::string& target) {
    if (target == "lavapipe") return r.cost_per_pixel;
    const auto it = r.target_costs.find(target);
    return it == r.target_costs.end() ? 0 : it->second;
}

} // namespace

double AccuracyBench::cost_ratio(const AccuracyRow& row, const std::string& target) const {
    for (const AccuracyRow& g : rows)
        if (g.axis == row.axis && g.gold) {
            const double gold = cost_on(g, target), own = cost_on(row, target);
            return gold > 0 && own > 0 ? own / gold : 0;
        }
    return 0;
}

std::string AccuracyBench::disagreement(const AccuracyRow& row) const {
    std::string cheaper, dearer;
    for (const std::string& t : targets) {
        const double r = cost_ratio(row, t);
        if (r == 0 || std::abs(r - 1) <= 0.005) continue;
        std::string& list = r < 1 ? cheaper : dearer;
        list += (list.empty() ? "" : ", ") + t;
    }
    if (cheaper.empty() || dearer.empty()) return "";
    return "cheaper than the gold on " + cheaper + "; dearer on " + dearer;
}

namespace {

// Instructions per pixel of every row's variant, from one valgrind worker; "" or the failure.
std::string add_costs(uint32_t cost_size, AccuracyBench& bench) {
    std::vector<Variant> variants;
    std::set<std::string> keys;
    for (const AccuracyRow& r : bench.rows)
        if (!r.skipped() && keys.insert(r.variant.key()).second) variants.push_back(r.variant);
    std::string error;
    const auto counts = count_draw_costs(variants, cost_size, "", "beach", &error, true);
    if (!counts) return "instruction count: " + error;
    for (AccuracyRow& r : bench.rows)
        if (auto it = counts->find(r.variant.key()); it != counts->end())
            r.cost_per_pixel = double(it->second) / (double(cost_size) * cost_size);
    return "";
}

// Each measured row's fragment cost on every AMD target, built as the row renders (the half row
// strict half); "" or the failure.
std::string add_gpu_costs(const std::vector<GpuTarget>& targets, AccuracyBench& bench) {
    std::vector<VariantBuild> builds;
    std::vector<std::string> keys;
    std::vector<AccuracyRow*> rows;
    for (AccuracyRow& r : bench.rows) {
        if (r.skipped()) continue;
        builds.push_back(build_variant(r.variant, nullptr,
                                       EmitOptions{r.variant.choice("precision") == "half"}));
        keys.push_back(r.axis + "=" + r.choice);
        rows.push_back(&r);
    }
    const GlslFragmentCosts costs = glsl_fragment_costs(targets, builds, keys);
    if (!costs.ok()) return costs.error;
    for (size_t t = 0; t < targets.size(); ++t) {
        for (size_t i = 0; i < rows.size(); ++i) {
            if (costs.costs[t][i]) {
                rows[i]->target_costs[targets[t].name] = *costs.costs[t][i];
                continue;
            }
            // The half row on a family without 16-bit arithmetic.
            rows[i]->note +=
                (rows[i]->note.empty() ? "" : "; ") + targets[t].name + ": no 16-bit arithmetic";
        }
        bench.targets.push_back(targets[t].name);
    }
    return "";
}

std::string csv_row(const AccuracyRow& r) {
    const bool error = r.gold || r.approximation();
    return fmt::format("{},{},{},\"{}\",{:.2f},{:.4f},{:.4f},{:.4f},{},{},{},{},{},{},\"{}\"\n",
                       r.axis, r.choice, r.gold, r.relation, r.cost_per_pixel, r.time.ratio,
                       r.time.lo, r.time.hi, r.spirv_instructions,
                       error ? fmt::format("{:.6g}", r.worst.max_abs) : "",
                       error ? fmt::format("{:.6g}", r.worst.rmse) : "",
                       error ? fmt::format("{:.4f}", r.worst.ciede2000_mean) : "",
                       error ? fmt::format("{:.4f}", r.worst.ciede2000_p99) : "",
                       error ? r.worst_view : "", r.note);
}

nlohmann::ordered_json json_row(const AccuracyRow& r) {
    nlohmann::ordered_json row = {{"axis", r.axis},
                                  {"choice", r.choice},
                                  {"gold", r.gold},
                                  {"relation", r.relation},
                                  {"cost_per_pixel", r.cost_per_pixel},
                                  {"time_ratio", {r.time.ratio, r.time.lo, r.time.hi}},
                                  {"spirv_instructions", r.spirv_instructions},
                                  {"note", r.note}};
    if (r.gold || r.approximation())
        row["error"] = {{"max_abs", r.worst.max_abs},
                        {"rmse", r.worst.rmse},
                        {"ciede2000_mean", r.worst.ciede2000_mean},
                        {"ciede2000_p99", r.worst.ciede2000_p99},
                        {"worst_view", r.worst_view}};
    return row;
}

} // namespace

AccuracyBench bench_accuracy(VulkanRunner& runner, const AccuracyBenchRequest& request) {
    std::vector<std::pair<std::string, SyntheticScene>> views;
    for (const SceneView& v : scene_views())
        views.emplace_back(v.name, make_synthetic_scene(request.size, request.size, v));
    AccuracyBench bench = run_accuracy_bench(runner, views, request.rounds, request.draws);
    bench.reference = accuracy_reference_variant();
    if (!bench.ok()) return bench;
    if (request.cost) bench.error = add_costs(request.cost_size, bench);
    if (request.cost && bench.ok()) bench.targets.push_back("lavapipe");
    if (bench.ok() && !request.gpu_targets.empty())
        bench.error = add_gpu_costs(request.gpu_targets, bench);
    if (!bench.ok()) return bench;
    // With targets: each one's cost and ratio to the gold, and where they rank it differently.
    std::string target_columns;
    for (const std::string& t : bench.targets)
        target_columns += fmt::format(",cost_{0},cost_ratio_{0}", t);
    bench.csv = "axis,choice,gold,relation,cost_per_pixel,time_ratio,time_lo,time_hi,"
                "spirv_instructions,max_abs,rmse,ciede2000_mean,ciede2000_p99,worst_view,note" +
                target_columns + (bench.targets.size() > 1 ? ",targets_disagree\n" : "\n");
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const AccuracyRow& r : bench.rows) {
        std::string row = csv_row(r);
        row.pop_back(); // the newline
        nlohmann::ordered_json j = json_row(r);
        for (const std::string& t : bench.targets) {
            row += fmt::format(",{:.2f},{:.4f}", cost_on(r, t), bench.cost_ratio(r, t));
            j["targets"][t] = {{"cost_per_pixel", cost_on(r, t)},
                               {"ratio_to_gold", bench.cost_ratio(r, t)}};
        }
        if (bench.targets.size() > 1) {
            row += ",\"" + bench.disagreement(r) + "\"";
            j["targets_disagree"] = bench.disagreement(r);
        }
        bench.csv += row + "\n";
        rows.push_back(j);
    }
    const nlohmann::ordered_json doc = {{"reference", bench.reference.key()},
                                        {"size", request.size},
                                        {"views", bench.views},
                                        {"rounds", request.rounds},
                                        {"draws", request.draws},
                                        {"device", runner.device_info().name},
                                        {"rows", rows}};
    bench.json = doc.dump(2) + "\n";
    return bench;
}

} // namespace watergen
