#include "watergen/eval/bench/accuracy_bench.h"

#include <algorithm>

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

} // namespace watergen
