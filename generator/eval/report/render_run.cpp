#include "watergen/eval/report/render_run.h"

#include <algorithm>

namespace watergen {

namespace {

RenderReportInfo report_info(const VulkanRunner& runner, const RenderRequest& request) {
    return {request.preset ? request.preset->name : "",
            request.shader_cache,
            runner.device_info(),
            request.width,
            request.height,
            request.exposure,
            request.view};
}

} // namespace

std::filesystem::path render_directory(const std::filesystem::path& out, const Variant& variant,
                                       const std::string& view) {
    const std::string stem = variant.file_stem();
    return out / (view == beach_view().name ? stem : stem + "_view-" + view);
}

RenderRun run_render(VulkanRunner& runner, const RenderRequest& request) {
    RenderRun run;
    const Variant& v = request.variant;
    auto fail = [&run](std::string error) {
        run.error = std::move(error);
        run.status = RunStatus::Failed;
        return std::move(run);
    };
    const VariantBuild build =
        build_variant(v, request.preset, EmitOptions{false, {}, request.unroll});
    run.diagnostics = build.diagnostics;
    if (!build.ok()) return fail("");
    SyntheticScene scene =
        preset_scene(request.width, request.height, request.preset, request.view);
    RenderExtras extras;
    if (has_caustics(v)) {
        run.caustics =
            prepare_render_caustics(runner, v, build, scene, request.draws, request.preset);
        const RenderCaustics& c = *run.caustics;
        if (c.pass)
            run.diagnostics.insert(run.diagnostics.end(), c.pass->diagnostics.begin(),
                                   c.pass->diagnostics.end());
        std::string error = c.error;
        const auto files =
            c.ok() ? render_caustics_files(c, float(request.exposure), &error) : std::nullopt;
        if (!files) return fail(v.key() + ": " + error);
        extras.files = *files;
        extras.json["caustics"] = render_caustics_json(c);
    }
    RenderSettings settings{request.width, request.height, request.draws, true};
    settings.float_bound = true;
    settings.tolerance = request.tolerance;
    run.render = render_variant(runner, build, scene, settings);
    if (!run.render.ok()) return fail(run.render.key + ": " + run.render.error);
    // The pixel furthest over its allowance, traced to the operations its float rounding
    // depends on most (one evaluation of its quad per operation).
    if (run.render.agreement[0].over_tolerance > 0) {
        const PixelLocation at = run.render.agreement[0].worst;
        run.worst = attribute_float_error(build.shader.fragment, "color", scene.eval_inputs(),
                                          request.width, request.height, at.x, at.y);
    }
    extras.json["agreement"] = agreement_json(run.render, run.worst ? &*run.worst : nullptr);
    run.dir = render_directory(request.out, v, request.view);
    run.info = report_info(runner, request);
    if (auto e = write_render_report(run.dir, run.render, run.info, extras)) return fail(*e);
    run.gpu_only_non_finite = gpu_only_non_finite_pixels(run.render);
    return run;
}

HalfRenderRun run_strict_half_render(VulkanRunner& runner, const RenderRequest& request) {
    HalfRenderRun run;
    const SyntheticScene scene =
        preset_scene(request.width, request.height, request.preset, request.view);
    run.half = render_strict_half(runner, request.variant, request.preset, scene,
                                  {request.width, request.height, request.draws});
    if (!run.half.ok()) {
        run.error = run.half.key + ": " + run.half.error;
        run.status = RunStatus::Failed;
        return run;
    }
    run.dir = render_directory(request.out, request.variant, request.view);
    run.info = report_info(runner, request);
    if (auto e = write_half_render_report(run.dir, run.half, run.info)) {
        run.error = *e;
        run.status = RunStatus::Failed;
        return run;
    }
    run.gpu_only_non_finite = std::max(run.half.vs_cpu_half[0].nan_inf_where_reference_finite,
                                       run.half.vs_cpu_half[1].nan_inf_where_reference_finite);
    return run;
}

} // namespace watergen
