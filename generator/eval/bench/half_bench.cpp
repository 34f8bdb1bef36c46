#include "watergen/eval/bench/half_bench.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/plan/covering_array.h"

namespace watergen {

namespace {

nlohmann::ordered_json agreement_json(const HalfAgreement& a, double max_abs) {
    return {{"values", a.values},
            {"equal", a.equal},
            {"within_1_ulp", a.within_1},
            {"max_ulps", a.max_ulps},
            {"max_abs", max_abs}};
}

nlohmann::ordered_json error_json(const ImageErrorStats& s) {
    return {{"max_abs", s.max_abs},
            {"ciede2000_mean", s.ciede2000_mean},
            {"ciede2000_p99", s.ciede2000_p99},
            {"nan_inf_pixels", s.nan_inf_pixels}};
}

std::string csv_row(const HalfBenchRow& r) {
    const HalfAgreement &g = r.vs_cpu_half[0], &h = r.vs_cpu_half[1];
    const uint64_t nan_inf = r.vs_full[0].nan_inf_pixels + r.vs_full[1].nan_inf_pixels;
    return fmt::format("\"{}\",{:.3f},{:.3f},{},{:.3f},{:.3f},{},{:.6g},{:.5f},{:.5f},"
                       "{:.6g},{:.6g},{:.5f},{:.5f},{}\n",
                       r.key, percent(g.equal, g.values), percent(g.within_1, g.values), g.max_ulps,
                       percent(h.equal, h.values), percent(h.within_1, h.values), h.max_ulps,
                       r.vs_full[0].max_abs, r.vs_full[0].ciede2000_mean,
                       r.vs_full[0].ciede2000_p99, r.vs_full[1].max_abs, r.cpu_half_vs_full.max_abs,
                       r.cpu_half_vs_full.ciede2000_mean, r.cpu_half_vs_full.ciede2000_p99,
                       nan_inf);
}

nlohmann::ordered_json json_row(const HalfBenchRow& r) {
    return {{"variant", r.key},
            {"glsl_vs_cpu_half", agreement_json(r.vs_cpu_half[0], r.max_abs_vs_cpu_half[0])},
            {"hlsl_vs_cpu_half", agreement_json(r.vs_cpu_half[1], r.max_abs_vs_cpu_half[1])},
            {"glsl_vs_full", error_json(r.vs_full[0])},
            {"hlsl_vs_full", error_json(r.vs_full[1])},
            {"cpu_half_vs_full", error_json(r.cpu_half_vs_full)}};
}

} // namespace

double percent(uint64_t part, uint64_t whole) {
    return whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

HalfBench run_half_bench(VulkanRunner& runner, uint32_t size, uint32_t draws) {
    HalfBench bench;
    bench.size = size;
    const SyntheticScene scene = make_synthetic_scene(size, size);
    for (const Variant& v : pairwise_covering_variants()) {
        if (v.choice("precision") != "half") continue;
        const HalfRender h = render_strict_half(runner, v, nullptr, scene, {size, size, draws});
        if (!h.ok()) {
            bench.diagnostics = h.diagnostics;
            bench.error = h.key + ": " + h.error;
            return bench;
        }
        bench.rows.push_back({h.key,
                              h.ulps_vs_cpu_half,
                              {h.vs_cpu_half[0].max_abs, h.vs_cpu_half[1].max_abs},
                              h.vs_full,
                              h.cpu_half_vs_full});
    }
    bench.csv = "variant,glsl_equal_pct,glsl_within_1_ulp_pct,glsl_max_ulps,"
                "hlsl_equal_pct,hlsl_within_1_ulp_pct,hlsl_max_ulps,"
                "glsl_vs_full_max_abs,glsl_vs_full_de_mean,glsl_vs_full_de_p99,"
                "hlsl_vs_full_max_abs,cpu_half_vs_full_max_abs,"
                "cpu_half_vs_full_de_mean,cpu_half_vs_full_de_p99,gpu_nan_inf_pixels\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const HalfBenchRow& r : bench.rows) {
        bench.csv += csv_row(r);
        rows.push_back(json_row(r));
    }
    const nlohmann::ordered_json doc = {
        {"size", size}, {"device", runner.device_info().name}, {"rows", rows}};
    bench.json = doc.dump(2) + "\n";
    return bench;
}

} // namespace watergen
