#include "watergen/eval/draw/half_render.h"

#include "watergen/ir/cpu/cpu_evaluator.h"
#include "watergen/pipeline/variant/variant_build.h"

namespace watergen {

HalfAgreement half_agreement(const ImageRGBA32F& test, const ImageRGBA32F& reference) {
    HalfAgreement a;
    if (test.rgba.size() != reference.rgba.size()) return a;
    for (size_t p = 0; p < test.rgba.size() / 4; ++p)
        for (size_t c = 0; c < 3; ++c)
            a.add(test.rgba[p * 4 + c], reference.rgba[p * 4 + c], p);
    return a;
}

HalfRender render_strict_half(VulkanRunner& runner, const Variant& variant, const Preset* preset,
                              const SyntheticScene& scene, const RenderSettings& settings) {
    HalfRender out;
    out.key = variant.key();
    if (variant.choice("precision") != "half") {
        out.error = "strict half renders a precision=half variant; this one is precision=" +
                    variant.choice("precision");
        return out;
    }
    RenderSettings gpu_only = settings;
    gpu_only.cpu_float = false;
    gpu_only.cpu_double = false;
    // Builds and renders one variant into `render`, keeping its graph in `graph`; false (and
    // out's error) on failure.
    Graph strict_graph, full_graph;
    auto build_and_render = [&](const Variant& v, bool strict, const char* what,
                                VariantRender& render, Graph& graph) {
        VariantBuild build = build_variant(v, preset, EmitOptions{strict});
        if (!build.ok()) {
            out.diagnostics = build.diagnostics;
            out.error = std::string("the ") + what + " build failed";
            return false;
        }
        render = render_variant(runner, build, scene, gpu_only);
        if (!render.ok()) out.error = std::string(what) + ": " + render.error;
        graph = std::move(build.shader.fragment);
        return render.ok();
    };
    if (!build_and_render(variant, true, "strict-half", out.strict, strict_graph)) return out;
    Variant full_variant = variant;
    set_choice(full_variant, "precision", "full");
    if (!build_and_render(full_variant, false, "precision=full", out.full, full_graph)) return out;

    // Strict half changes only emission: the CPU model evaluates the same graph.
    const EvalResult half = evaluate_image(strict_graph, "color", scene.eval_inputs(),
                                           settings.width, settings.height, EvalPrecision::Half);
    if (!half.ok()) {
        out.error = "CPU evaluator: " + half.error;
        return out;
    }
    out.cpu_half = to_image(half, settings.width, settings.height);
    const ImageRGBA32F& reference = out.full.gpu_image[0];
    for (size_t i = 0; i < 2; ++i) {
        out.vs_cpu_half[i] = compare_images(out.strict.gpu_image[i], out.cpu_half);
        out.ulps_vs_cpu_half[i] = half_agreement(out.strict.gpu_image[i], out.cpu_half);
        out.vs_full[i] = compare_images(out.strict.gpu_image[i], reference);
    }
    out.cpu_half_vs_full = compare_images(out.cpu_half, reference);
    return out;
}

} // namespace watergen
