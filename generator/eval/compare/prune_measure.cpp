#include "watergen/eval/compare/prune_measure.h"

#include <algorithm>
#include <cmath>

#include "watergen/ir/emit/uniform_layout.h"
#include "watergen/ir/fold/ir_fold.h"

namespace watergen {

PrunePair build_prune_pair(const Material& m, const ScenePlan& plan, const Variant& v) {
    PrunePair out;
    WaterShader unpruned = m.compose(v);
    if (has_errors(unpruned.fragment.diagnostics())) {
        out.error = "variant does not compose: " + unpruned.fragment.diagnostics().front().message;
        return out;
    }
    WaterShader pruned = unpruned;
    FoldResult folded = fold_graph(unpruned.fragment, plan.facts);
    out.live_before = folded.report.live_before;
    out.live_after = folded.report.live_after;
    pruned.fragment = std::move(folded.graph);
    out.unpruned = build_shader(std::move(unpruned));
    out.pruned = build_shader(std::move(pruned));
    if (!out.unpruned.ok() || !out.pruned.ok()) {
        const VariantBuild& bad = out.unpruned.ok() ? out.pruned : out.unpruned;
        out.error = std::string(out.unpruned.ok() ? "pruned" : "unpruned") + " build failed: " +
                    (bad.diagnostics.empty() ? std::string("?")
                                             : format_diagnostic(bad.diagnostics.front()));
    }
    return out;
}

PruneMeasurement pair_sizes(const ScenePlan& plan, const Variant& v, const PrunePair& pair) {
    PruneMeasurement out;
    out.scene = plan.scene.name;
    out.key = v.key();
    out.live_before = pair.live_before;
    out.live_after = pair.live_after;
    const auto& a = pair.unpruned.languages[0].fragment.toolchain;
    const auto& b = pair.pruned.languages[0].fragment.toolchain;
    out.spirv_unpruned = a.instruction_count;
    out.spirv_pruned = b.instruction_count;
    out.spirv_opt_unpruned = a.instruction_count_optimized;
    out.spirv_opt_pruned = b.instruction_count_optimized;
    return out;
}

std::optional<double> pruned_difference(const ImageRGBA32F& pruned, const ImageRGBA32F& unpruned,
                                        std::string* error) {
    const ImageErrorStats s = compare_images(pruned, unpruned);
    if (!s.error.empty() || s.nan_inf_pixels != s.reference_nan_inf_pixels) {
        *error = "images cannot be compared: " +
                 (s.error.empty() ? std::string("non-finite pixels differ") : s.error);
        return std::nullopt;
    }
    return s.max_abs;
}

PruneMeasurement measure_pruning(VulkanRunner& runner, const Material& m, const ScenePlan& plan,
                                 const Variant& v, const SyntheticScene& scene,
                                 const RenderSettings& settings) {
    const PrunePair pair = build_prune_pair(m, plan, v);
    PruneMeasurement out = pair_sizes(plan, v, pair);
    out.error = pair.error;
    if (!out.ok()) return out;
    RenderSettings s = settings;
    s.cpu_double = false;
    s.cpu_float = true;
    const VariantRender ra = render_variant(runner, pair.unpruned, scene, s);
    const VariantRender rb = render_variant(runner, pair.pruned, scene, s);
    for (const VariantRender* r : {&ra, &rb})
        if (!r->ok()) {
            out.error = "render: " + r->error;
            return out;
        }
    double* into[3] = {&out.max_abs_glsl, &out.max_abs_hlsl, &out.max_abs_cpu};
    const std::pair<const ImageRGBA32F*, const ImageRGBA32F*> images[3] = {
        {&rb.gpu_image[0], &ra.gpu_image[0]},
        {&rb.gpu_image[1], &ra.gpu_image[1]},
        {&rb.cpu_float, &ra.cpu_float}};
    for (int i = 0; i < 3; ++i) {
        const auto d = pruned_difference(*images[i].first, *images[i].second, &out.error);
        if (!d) return out;
        *into[i] = *d;
    }
    return out;
}

} // namespace watergen
