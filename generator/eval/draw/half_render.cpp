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

StrictHalfBuilds build_strict_half(const Variant& variant, const Preset* preset) {
    StrictHalfBuilds out;
    out.key = variant.key();
    if (variant.choice("precision") != "half") {
        out.error = "strict half renders a precision=half variant; this one is precision=" +
                    variant.choice("precision");
        return out;
    }
    out.strict = build_variant(variant, preset, EmitOptions{true});
    if (!out.strict.ok()) {
        out.diagnostics = out.strict.diagnostics;
        out.error = "the strict-half build failed";
        return out;
    }
    Variant full_variant = variant;
    set_choice(full_variant, "precision", "full");
    out.full = build_variant(full_variant, preset, EmitOptions{false});
    if (!out.full.ok()) {
        out.diagnostics = out.full.diagnostics;
        out.error = "the precision=full build failed";
    }
    return out;
}

HalfRender render_strict_half(VulkanRunner& runner, const Variant& variant, const Preset* preset,
                              const SyntheticScene& scene, const RenderSettings& settings) {
    const StrictHalfBuilds builds = build_strict_half(variant, preset);
    if (!builds.ok()) {
        HalfRender out;
        out.key = builds.key;
        out.diagnostics = builds.diagnostics;
        out.error = builds.error;
        return out;
    }
    return render_strict_half(runner, builds, scene, settings);
}

HalfRender render_strict_half(VulkanRunner& runner, const StrictHalfBuilds& builds,
                              const SyntheticScene& scene, const RenderSettings& settings) {
    HalfRender out;
    out.key = builds.key;
    RenderSettings gpu_only = settings;
    gpu_only.cpu_float = false;
    gpu_only.cpu_double = false;
    out.strict = render_variant(runner, builds.strict, scene, gpu_only);
    if (!out.strict.ok()) {
        out.error = "strict-half: " + out.strict.error;
        return out;
    }
    out.full = render_variant(runner, builds.full, scene, gpu_only);
    if (!out.full.ok()) {
        out.error = "precision=full: " + out.full.error;
        return out;
    }

    // Strict half changes only emission: the CPU model evaluates the same graph.
    const EvalResult half =
        evaluate_image(builds.strict.shader.fragment, "color", scene.eval_inputs(), settings.width,
                       settings.height, EvalPrecision::Half);
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
