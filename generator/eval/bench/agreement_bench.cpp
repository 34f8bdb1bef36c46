#include "watergen/eval/bench/agreement_bench.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/ir/cpu/float_error.h"
#include "watergen/plan/covering_array.h"

namespace watergen {

namespace {

nlohmann::ordered_json side_json(const Agreement& a, double max_abs) {
    return {{"max_abs", max_abs},
            {"over_tolerance", a.over_tolerance},
            {"over_tolerance_and_bound", a.over_bound},
            {"max_bound", a.max_bound},
            {"worst_at", {a.worst.x, a.worst.y}},
            {"worst_difference", a.worst_difference},
            {"worst_bound", a.worst_bound}};
}

std::string csv_row(const AgreementBenchRow& r) {
    const Agreement &g = r.agreement[0], &h = r.agreement[1];
    return fmt::format("\"{}\",{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{},{},{},{},{:.6g},{},\"{}\"\n",
                       r.key, r.glsl_vs_hlsl, r.vs_cpu_float[0], r.vs_cpu_float[1],
                       r.glsl_vs_cpu_double, r.cpu_float_vs_double, g.over_tolerance, g.over_bound,
                       h.over_tolerance, h.over_bound, g.max_bound, r.gpu_nan_inf, r.cause);
}

} // namespace

AgreementBench run_agreement_bench(VulkanRunner& runner, uint32_t size, double tolerance) {
    AgreementBench bench;
    bench.size = size;
    bench.tolerance = tolerance;
    const SyntheticScene scene = make_synthetic_scene(size, size);
    RenderSettings settings{size, size, 1, true};
    settings.float_bound = true;
    settings.tolerance = tolerance;
    for (const Variant& v : pairwise_covering_variants()) {
        const VariantBuild build = build_variant(v);
        if (!build.ok()) {
            bench.diagnostics = build.diagnostics;
            bench.error = v.key() + ": the variant did not build";
            return bench;
        }
        const VariantRender r = render_variant(runner, build, scene, settings);
        if (!r.ok()) {
            bench.error = r.key + ": " + r.error;
            return bench;
        }
        bench.rows.push_back(
            {r.key,
             r.glsl_vs_hlsl.max_abs,
             {r.glsl_vs_cpu_float.max_abs, r.hlsl_vs_cpu_float.max_abs},
             r.glsl_vs_cpu_double.max_abs,
             check_agreement(r.cpu_float, r.cpu_double, {}, 0.0).worst_difference,
             r.agreement,
             r.glsl_vs_cpu_float.nan_inf_pixels + r.hlsl_vs_cpu_float.nan_inf_pixels,
             ""});
        if (r.agreement[0].over_tolerance > 0) {
            const PixelLocation at = r.agreement[0].worst;
            const PixelAttribution a = attribute_float_error(
                build.shader.fragment, "color", scene.eval_inputs(), size, size, at.x, at.y, 1);
            if (a.ok() && !a.effects.empty()) {
                const EvalSite& e = a.effects.front().what;
                bench.rows.back().cause = e.origin + " " + op_name(e.op) + "(" + e.operands + ")";
            }
        }
    }
    bench.csv = "variant,glsl_vs_hlsl_max_abs,glsl_vs_cpu_float_max_abs,"
                "hlsl_vs_cpu_float_max_abs,glsl_vs_cpu_double_max_abs,"
                "cpu_float_vs_double_max_abs,glsl_over_tolerance,glsl_over_bound,"
                "hlsl_over_tolerance,hlsl_over_bound,max_bound,gpu_nan_inf_pixels,cause\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const AgreementBenchRow& r : bench.rows) {
        bench.csv += csv_row(r);
        rows.push_back({{"variant", r.key},
                        {"glsl_vs_hlsl_max_abs", r.glsl_vs_hlsl},
                        {"glsl_vs_cpu_float", side_json(r.agreement[0], r.vs_cpu_float[0])},
                        {"hlsl_vs_cpu_float", side_json(r.agreement[1], r.vs_cpu_float[1])},
                        {"glsl_vs_cpu_double_max_abs", r.glsl_vs_cpu_double},
                        {"cpu_float_vs_double_max_abs", r.cpu_float_vs_double},
                        {"gpu_nan_inf_pixels", r.gpu_nan_inf},
                        {"worst_pixel_cause", r.cause}});
    }
    const nlohmann::ordered_json doc = {{"size", size},
                                        {"tolerance", tolerance},
                                        {"device", runner.device_info().name},
                                        {"rows", rows}};
    bench.json = doc.dump(2) + "\n";
    return bench;
}

} // namespace watergen
