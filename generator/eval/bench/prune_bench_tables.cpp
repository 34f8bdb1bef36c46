// prune.csv and prune.json of `watergen bench prune` (prune_bench.h).
#include "watergen/eval/bench/prune_bench.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace watergen {

namespace {

std::string csv_row(const std::string& scene, const PruneBenchRow& row,
                    const std::vector<GpuTarget>& targets) {
    const PruneMeasurement& r = row.measurement;
    std::string target_cells;
    for (const GpuTarget& t : targets) {
        const auto it = row.target_costs.find(t.name);
        if (it == row.target_costs.end())
            target_cells += ",,";
        else
            target_cells += fmt::format(",{:.0f},{:.0f}", it->second.first, it->second.second);
    }
    std::string line = fmt::format(
        "{},\"{}\",{},{},{},{},{},{},{:.2f},{:.2f},{:.5f},{:.5f},{:.5f},{:.3g},"
        "{:.3g},{:.3g}\n",
        scene, row.variant.key(), r.live_before, r.live_after, r.spirv_unpruned, r.spirv_pruned,
        r.spirv_opt_unpruned, r.spirv_opt_pruned, row.cost_unpruned, row.cost_pruned,
        row.time.ratio, row.time.lo, row.time.hi, r.max_abs_glsl, r.max_abs_hlsl, r.max_abs_cpu);
    line.pop_back(); // the newline, after the target columns
    return line + target_cells + "\n";
}

// Per AMD target: [unpruned, pruned] fragment instructions per pixel (ACO, loops weighted).
nlohmann::ordered_json targets_json(const PruneBenchRow& row) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& [t, c] : row.target_costs)
        j[t] = {c.first, c.second};
    return j;
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
        {"max_abs", {{"glsl", r.max_abs_glsl}, {"hlsl", r.max_abs_hlsl}, {"cpu", r.max_abs_cpu}}},
        {"targets", targets_json(row)}};
}

} // namespace

void add_prune_tables(const PruneBenchOptions& o, const std::string& device,
                      PruneBenchResult& result) {
    result.csv = "scene,variant,ir_before,ir_after,spirv_unpruned,spirv_pruned,spirv_opt_unpruned,"
                 "spirv_opt_pruned,instructions_per_pixel_unpruned,instructions_per_pixel_pruned,"
                 "time_ratio,time_ratio_lo,time_ratio_hi,max_abs_glsl,max_abs_hlsl,max_abs_cpu";
    for (const GpuTarget& t : o.gpu_targets)
        result.csv += fmt::format(",{0}_unpruned,{0}_pruned", t.name);
    result.csv += "\n";
    nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
    for (const PruneBenchScene& s : result.scenes) {
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        for (const PruneBenchRow& row : s.rows) {
            result.csv += csv_row(s.name, row, o.gpu_targets);
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
                            {"time", s.time},
                            {"targets", s.target_cost}}},
                          {"rows", rows}});
        if (!s.complete) break;
    }
    const nlohmann::ordered_json doc = {
        {"size", o.size},           {"rounds", o.rounds},        {"draws", o.draws},
        {"cost_size", o.cost_size}, {"cost_aa", result.cost_aa}, {"device", device},
        {"scenes", scenes}};
    result.json = doc.dump(2) + "\n";
}

} // namespace watergen
