#include "watergen/eval/bench/unroll_bench.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "watergen/eval/draw/variant_render.h"
#include "watergen/eval/measure/interleaved_timing.h" // median()
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/water/axis_registry.h"

namespace watergen {

namespace {

size_t line_count(const std::string& text) {
    return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

// Renders one side once: both language paths, GPU only.
std::string render_side(VulkanRunner& runner, const VariantBuild& build,
                        const SyntheticScene& scene, uint32_t size, uint32_t draws,
                        UnrollSide& side) {
    RenderSettings settings{size, size, draws, false, false};
    const VariantRender r = render_variant(runner, build, scene, settings);
    if (!r.ok()) return r.key + ": " + r.error;
    for (const auto& gpu : r.gpu) {
        side.first_draw_ms.push_back(gpu.first_draw_ms);
        side.steady_draw_ms.push_back(gpu.steady_draw_ms);
        side.pipeline_ms.push_back(gpu.pipeline_ms);
    }
    return "";
}

// Each sample of `a` over the same sample of `b`.
std::vector<double> ratios(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> out;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
        out.push_back(b[i] > 0 ? a[i] / b[i] : 0.0);
    return out;
}

nlohmann::ordered_json targets_json(const UnrollSide& s) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& [t, c] : s.targets)
        j[t] = {{"instructions", c.instructions},
                {"per_pixel", c.per_pixel ? *c.per_pixel : c.instructions},
                {"vgprs", c.vgprs},
                {"waves_per_simd", c.waves_per_simd},
                {"code_bytes", c.code_bytes}};
    return j;
}

nlohmann::ordered_json side_json(const UnrollSide& s) {
    return {{"glsl_lines", s.glsl_lines},         {"spirv_words", s.spirv_words},
            {"instructions", s.instructions},     {"first_draw_ms", s.first_draw_ms},
            {"steady_draw_ms", s.steady_draw_ms}, {"pipeline_ms", s.pipeline_ms},
            {"targets", targets_json(s)}};
}

// unroll.csv (a line per waves choice and hint, medians) and unroll.json (every sample).
void add_tables(UnrollBench& b, uint32_t draws, const std::string& device) {
    b.csv = "waves,hint,glsl_lines,spirv_words,instructions,first_draw_ms_median,"
            "steady_draw_ms_median,first_draw_ratio_median,steady_ratio_median";
    for (const std::string& t : b.targets)
        b.csv += fmt::format(",{0}_instructions,{0}_per_pixel,{0}_vgprs,{0}_waves_per_simd", t);
    b.csv += "\n";
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const auto& r : b.rows) {
        for (const auto& [hint, side] :
             {std::pair{"kept", &r.kept}, std::pair{"unrolled", &r.unrolled}}) {
            b.csv += fmt::format("{},{},{},{},{},{:.3f},{:.4f},{:.4f},{:.4f}", r.waves, hint,
                                 side->glsl_lines, side->spirv_words, side->instructions,
                                 median(side->first_draw_ms), median(side->steady_draw_ms),
                                 median(r.first_draw_ratio), median(r.steady_ratio));
            for (const std::string& t : b.targets) {
                const StageGpuCost& c = side->targets.at(t);
                b.csv += fmt::format(",{:.0f},{:.0f},{:.0f},{:.0f}", c.instructions,
                                     c.per_pixel ? *c.per_pixel : c.instructions, c.vgprs,
                                     c.waves_per_simd);
            }
            b.csv += "\n";
        }
        rows.push_back({{"waves", r.waves},
                        {"kept", side_json(r.kept)},
                        {"unrolled", side_json(r.unrolled)},
                        {"kept_again", side_json(r.kept_again)},
                        {"first_draw_ratio", r.first_draw_ratio},
                        {"first_draw_aa", r.first_draw_aa},
                        {"steady_ratio", r.steady_ratio},
                        {"steady_aa", r.steady_aa}});
    }
    const nlohmann::ordered_json j = {{"size", b.size},
                                      {"rounds", b.rounds},
                                      {"draws", draws},
                                      {"device", device},
                                      {"rows", rows}};
    b.json = j.dump(2) + "\n";
}

// Both shaders' fragment stage on each AMD target; "" or the failure.
std::string add_gpu_costs(const std::vector<GpuTarget>& targets,
                          const std::array<VariantBuild, 2>& builds, const std::string& waves,
                          UnrollBenchRow& row) {
    const std::array<LoopUnroll, 2> unroll = {LoopUnroll::None, LoopUnroll::All};
    const std::array<UnrollSide*, 2> sides = {&row.kept, &row.unrolled};
    for (size_t s = 0; s < 2; ++s) {
        const auto runs = variant_gpu_costs(targets, {&builds[s]}, {waves},
                                            std::filesystem::temp_directory_path(), unroll[s]);
        for (const TargetCosts& t : runs) {
            if (!t.run.ok()) return t.run.error;
            const StageGpuCost* f = t.costs[0].stage("fragment");
            if (!t.costs[0].ok() || !f) return waves + ": " + t.costs[0].error;
            sides[s]->targets[t.run.target.name] = *f;
        }
    }
    row.kept_again.targets = row.kept.targets;
    return "";
}

} // namespace

UnrollBench run_unroll_bench(VulkanRunner& runner, uint32_t size, uint32_t rounds, uint32_t draws,
                             const std::vector<GpuTarget>& targets) {
    UnrollBench bench;
    for (const GpuTarget& t : targets)
        bench.targets.push_back(t.name);
    bench.size = size;
    bench.rounds = rounds;
    const SyntheticScene scene = make_synthetic_scene(size, size);
    for (const ChoiceInfo& choice : find_axis("waves")->choices) {
        const std::string& waves = choice.name;
        Variant v = default_variant();
        set_choice(v, "waves", waves);
        UnrollBenchRow row;
        row.waves = waves;
        std::array<VariantBuild, 2> builds = {
            build_variant(v, nullptr, EmitOptions{false, {}, LoopUnroll::None}),
            build_variant(v, nullptr, EmitOptions{false, {}, LoopUnroll::All})};
        std::array<UnrollSide*, 3> sides = {&row.kept, &row.unrolled, &row.kept_again};
        for (int s = 0; s < 2; ++s) {
            const VariantBuild& b = builds[static_cast<size_t>(s)];
            bench.diagnostics.insert(bench.diagnostics.end(), b.diagnostics.begin(),
                                     b.diagnostics.end());
            if (!b.ok()) return bench;
            const StageBuild& frag = b.languages[0].fragment;
            for (UnrollSide* side :
                 s == 0 ? std::vector{sides[0], sides[2]} : std::vector{sides[1]}) {
                side->glsl_lines = line_count(frag.source.source);
                side->spirv_words = frag.toolchain.spirv_optimized.size();
                side->instructions = frag.toolchain.instruction_count_optimized;
            }
        }
        if (!targets.empty()) {
            bench.error = add_gpu_costs(targets, builds, waves, row);
            if (!bench.error.empty()) return bench;
        }
        for (uint32_t round = 0; round < rounds; ++round)
            for (uint32_t k = 0; k < 3; ++k) {
                const uint32_t which = (k + round) % 3; // kept, unrolled, kept again, rotated
                const VariantBuild& b = builds[which == 1 ? 1 : 0];
                bench.error = render_side(runner, b, scene, size, draws, *sides[which]);
                if (!bench.error.empty()) return bench;
            }
        row.first_draw_ratio = ratios(row.unrolled.first_draw_ms, row.kept.first_draw_ms);
        row.first_draw_aa = ratios(row.kept_again.first_draw_ms, row.kept.first_draw_ms);
        row.steady_ratio = ratios(row.unrolled.steady_draw_ms, row.kept.steady_draw_ms);
        row.steady_aa = ratios(row.kept_again.steady_draw_ms, row.kept.steady_draw_ms);
        bench.rows.push_back(std::move(row));
    }
    add_tables(bench, draws, runner.device_info().name);
    return bench;
}

} // namespace watergen
