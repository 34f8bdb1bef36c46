#include "watergen/eval/report/render_run.h"

#include <algorithm>

#include <fmt/format.h>

namespace watergen {

namespace {

RenderReportInfo report_info(const VulkanRunner& runner, const RenderRequest& request) {
    return {request.preset ? request.preset->name : "",
            request.shader_cache,
            runner.device_info(),
            request.width,
            request.height,
            request.exposure,
            request.view,
            request.world_offset};
}

// Puts `values` into the scene, each checked against the variant's parameter of that name
// (a position as given, in the scene's own frame) and then moved by the scene's world offset
// (placed_scene_value); scene_position follows the eye they set, and the depth buffer is
// made again for the conventions and eye.
std::optional<std::string> set_values(SyntheticScene& scene, const WaterShader& shader,
                                      const std::map<std::string, std::vector<double>>& values) {
    for (const auto& [name, value] : values) {
        const Parameter* p = shader.fragment.find_parameter(name);
        if (shader.mesh) // a mesh stage's (the camera, the grid, the factors)
            for (const Graph* stage : shader.mesh->graphs())
                if (!p) p = stage->find_parameter(name);
        if (!p) return "--set " + name + ": not a parameter of this variant";
        if (value.size() != value_count(*p))
            return fmt::format("--set {}: {} value(s), expected {}", name, value.size(),
                               value_count(*p));
        for (double x : value) {
            if (!(x >= p->min && x <= p->max))
                return fmt::format("--set {}: {:g} is outside [{:g}, {:g}]", name, x, p->min,
                                   p->max);
            if (p->flag && x != 0 && x != 1)
                return fmt::format("--set {}: {:g}; expected 0 or 1 (a switch)", name, x);
        }
        scene.uniforms[name] = placed_scene_value(name, value, scene.view.world_offset);
    }
    if (!values.empty()) {
        follow_scene_eye(scene); // the eye moves over the scene, which stays
        add_depth_inputs(scene);
    }
    return std::nullopt;
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
        build_variant(v, request.preset, EmitOptions{false, {}, request.unroll, request.bindings});
    run.diagnostics = build.diagnostics;
    if (!build.ok()) return fail("");
    SyntheticScene scene = preset_scene(request.width, request.height, request.preset, request.view,
                                        request.world_offset);
    if (auto error = set_values(scene, build.shader, request.values)) {
        run.error = v.key() + ": " + *error;
        run.status = RunStatus::BadInput;
        return run;
    }
    RenderExtras extras;
    for (const auto& [name, value] : request.values)
        extras.json["values"][name] = value;
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
    settings.grid = request.grid;
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
    const SyntheticScene scene = preset_scene(request.width, request.height, request.preset,
                                              request.view, request.world_offset);
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
