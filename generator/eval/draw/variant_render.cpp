#include "watergen/eval/draw/variant_render.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "watergen/eval/draw/mesh_render.h"
#include "watergen/ir/cpu/float_error.h"

namespace watergen {

ImageRGBA32F to_image(const EvalResult& r, uint32_t width, uint32_t height) {
    ImageRGBA32F img;
    img.width = width;
    img.height = height;
    img.rgba.resize(size_t(width) * height * 4, 1.0f);
    for (size_t p = 0; p < size_t(width) * height; ++p)
        for (int c = 0; c < r.components && c < 4; ++c)
            img.rgba[p * 4 + c] = static_cast<float>(r.values[p * r.components + c]);
    return img;
}

RenderJob make_render_job(const LanguageBuild& lang, const SyntheticScene& scene,
                          const RenderSettings& settings) {
    if (!draws_mesh(lang)) return scene_inputs_job(lang, scene, settings);
    const WaterGrid grid =
        scene_grid(scene, settings.grid, lang.tessellated(), settings.width, settings.height);
    auto values = mesh_values(scene, grid, settings.width, settings.height);
    if (settings.tess_max > 0) values["tess_max"] = {settings.tess_max};
    return mesh_render_job(lang, scene, grid_mesh(grid), values, settings.width, settings.height,
                           settings.timed_draws);
}

RenderJob scene_inputs_job(const LanguageBuild& lang, const SyntheticScene& scene,
                           const RenderSettings& settings,
                           const std::map<std::string, std::vector<double>>* values) {
    RenderJob job;
    job.vertex_spirv = lang.vertex.toolchain.spirv_optimized;
    job.fragment_spirv = lang.fragment.toolchain.spirv_optimized;
    job.vertex_reflection = lang.vertex.toolchain.reflection;
    job.fragment_reflection = lang.fragment.toolchain.reflection;
    job.width = settings.width;
    job.height = settings.height;
    const ShaderInterface& in = lang.fragment.source.interface;
    const auto& block = values ? *values : scene.uniforms;
    job.uniforms = pack_uniforms(in.uniforms, in.parameters, block);
    job.specialization = specialization_values(in.specialization, block);
    for (const auto& t : in.textures)
        if (auto it = scene.textures.find(t.name); it != scene.textures.end())
            job.textures[t.name] = it->second;
    job.filter = TextureFilter::Linear;
    job.timed_draws = settings.timed_draws;
    return job;
}

std::vector<float> float_bound(const Graph& graph, const EvalInputs& inputs, uint32_t width,
                               uint32_t height, const EvalResult& double_image, std::string& error,
                               const EvalResult* float_image) {
    ErrorSpread spread = float_error_spread(graph, "color", inputs, width, height, double_image,
                                            kFloatBoundRuns, kFloatBoundRelative);
    if (!spread.ok()) {
        error = spread.error;
        return {};
    }
    // Plus an ulp of the pixel's value on either side (the last rounding alone), and the float
    // image's own distance from double when there is one.
    const auto comps = static_cast<size_t>(double_image.components);
    for (size_t p = 0; p < spread.per_pixel.size(); ++p) {
        double largest = 0, apart = 0;
        for (size_t c = 0; c < comps && c < 3; ++c) {
            const double v = double_image.values[p * comps + c];
            largest = std::max(largest, std::fabs(v));
            if (float_image)
                apart = std::max(apart, std::fabs(float_image->values[p * comps + c] - v));
        }
        spread.per_pixel[p] =
            static_cast<float>(kFloatBoundFactor * spread.per_pixel[p] + largest * 0x1p-22 + apart);
    }
    return std::move(spread.per_pixel);
}

VariantRender render_variant(VulkanRunner& runner, const VariantBuild& build,
                             const SyntheticScene& scene, const RenderSettings& settings) {
    VariantRender out;
    out.key = build.shader.variant.key();
    if (!build.ok()) {
        out.error = "variant did not build";
        return out;
    }
    if (scene.width != settings.width || scene.height != settings.height) {
        out.error = "scene size differs from the render size";
        return out;
    }
    if (build.shader.mesh) return render_mesh_against_surface(runner, build, scene, settings);
    runner.clear_validation_messages();
    for (size_t i = 0; i < 2; ++i) {
        out.gpu[i] = runner.render(make_render_job(build.languages[i], scene, settings));
        if (!out.gpu[i].ok) {
            out.error =
                std::string(to_string(build.languages[i].language)) + " path: " + out.gpu[i].error;
            return out;
        }
        out.gpu_image[i] = ImageRGBA32F{settings.width, settings.height, out.gpu[i].rgba};
    }
    out.validation_messages = runner.validation_messages();
    out.glsl_vs_hlsl = compare_images(out.gpu_image[0], out.gpu_image[1]);
    if (!settings.cpu_float) return out;

    const auto t0 = std::chrono::steady_clock::now();
    const EvalResult f = evaluate_image(build.shader.fragment, "color", scene.eval_inputs(),
                                        settings.width, settings.height, EvalPrecision::Float);
    out.cpu_float_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!f.ok()) {
        out.error = "CPU evaluator: " + f.error;
        return out;
    }
    out.cpu_float = to_image(f, settings.width, settings.height);
    out.glsl_vs_cpu_float = compare_images(out.gpu_image[0], out.cpu_float);
    out.hlsl_vs_cpu_float = compare_images(out.gpu_image[1], out.cpu_float);
    if (settings.cpu_double) {
        const EvalResult d = evaluate_image(build.shader.fragment, "color", scene.eval_inputs(),
                                            settings.width, settings.height, EvalPrecision::Double);
        if (!d.ok()) {
            out.error = "CPU evaluator: " + d.error;
            return out;
        }
        out.cpu_double = to_image(d, settings.width, settings.height);
        out.glsl_vs_cpu_double = compare_images(out.gpu_image[0], out.cpu_double);
        if (settings.float_bound) {
            std::string error;
            out.float_bound = float_bound(build.shader.fragment, scene.eval_inputs(),
                                          settings.width, settings.height, d, error);
            if (!error.empty()) {
                out.error = "CPU evaluator: " + error;
                return out;
            }
            for (size_t i = 0; i < 2; ++i)
                out.agreement[i] = check_agreement(out.gpu_image[i], out.cpu_float, out.float_bound,
                                                   settings.tolerance);
        }
    }
    return out;
}

} // namespace watergen
