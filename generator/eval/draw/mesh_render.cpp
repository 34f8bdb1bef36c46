#include "watergen/eval/draw/mesh_render.h"

#include <algorithm>
#include <cmath>

#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/emit/specialization.h"
#include "watergen/ir/emit/uniform_layout.h"
#include "watergen/ir/fold/ir_fold.h"
#include "watergen/water/presets.h"

namespace watergen {

WaterGrid scene_grid(const SyntheticScene& scene, const WaterGridDesc& desc, bool tessellated,
                     uint32_t width, uint32_t height) {
    const SceneCamera cam = scene_camera(scene.view, width, height);
    return water_grid(desc, cam.eye[0], cam.eye[2],
                      tessellated ? GridTopology::Patches : GridTopology::Triangles);
}

uint64_t grid_primitives(const WaterGrid& grid) {
    return grid.indices.size() / (grid.patch_control_points ? grid.patch_control_points : 3);
}

std::vector<double> morph_weights(const SyntheticScene& scene, const WaterGridDesc& desc,
                                  const WaterGrid& grid, uint32_t width, uint32_t height) {
    const SceneCamera cam = scene_camera(scene.view, width, height);
    const auto centres = water_grid_snap(desc, cam.eye[0], cam.eye[2]);
    const auto level_of = scene.uniforms.find("water_level");
    const double level = level_of == scene.uniforms.end() ? 0.0 : level_of->second.at(0);
    const double n = desc.ring_cells;
    std::vector<double> out(size_t(width) * height, -1.0);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            // The ray through the pixel centre, as synthetic_scene.cpp casts it.
            const double sx = (2.0 * (x + 0.5) / width - 1.0) * cam.tan_half_fov_y * cam.aspect;
            const double sy = (1.0 - 2.0 * (y + 0.5) / height) * cam.tan_half_fov_y;
            double d[3];
            for (int k = 0; k < 3; ++k)
                d[k] = cam.forward[k] + cam.right[k] * sx + cam.up[k] * sy;
            const double t = (level - cam.eye[1]) / d[1];
            if (!(t > 0) || !std::isfinite(t)) continue;
            const double px = cam.eye[0] + t * d[0], pz = cam.eye[2] + t * d[2];
            // The finest level whose square holds the point (an inner level covers the hole of
            // the one outside it).
            for (uint32_t k = 0; k < desc.levels; ++k) {
                const double h = desc.spacing * std::ldexp(1.0, int(k));
                const double cx = double(centres[k][0]) * 2 * h, cz = double(centres[k][1]) * 2 * h;
                if (std::max(std::abs(px - cx), std::abs(pz - cz)) >= n * h) continue;
                const double cells =
                    std::max(std::abs(px - cam.eye[0]), std::abs(pz - cam.eye[2])) / h;
                out[size_t(y) * width + x] = std::clamp(
                    (cells - grid.morph_start) / (grid.morph_end - grid.morph_start), 0.0, 1.0);
                break;
            }
        }
    return out;
}

bool draws_mesh(const LanguageBuild& lang) {
    return !lang.vertex.source.interface.varyings.empty();
}

MeshData grid_mesh(const WaterGrid& grid) {
    MeshData mesh;
    mesh.vertices = grid.vertices;
    mesh.attribute_sizes = {2, 3};
    mesh.indices = grid.indices;
    mesh.patch_control_points = grid.patch_control_points;
    return mesh;
}

std::map<std::string, std::vector<double>>
mesh_values(const SyntheticScene& scene, const WaterGrid& grid, uint32_t width, uint32_t height) {
    const SceneCamera cam = scene_camera(scene.view, width, height);
    std::map<std::string, std::vector<double>> values = scene.uniforms;
    values["mesh_camera_right"] = {cam.right[0], cam.right[1], cam.right[2]};
    values["mesh_camera_up"] = {cam.up[0], cam.up[1], cam.up[2]};
    values["mesh_camera_forward"] = {cam.forward[0], cam.forward[1], cam.forward[2]};
    values["mesh_projection"] = {1.0 / (cam.tan_half_fov_y * cam.aspect), 1.0 / cam.tan_half_fov_y};
    values["eye_position"] = {cam.eye[0], cam.eye[1], cam.eye[2]};
    values["mesh_pixel_angle"] = {2.0 * cam.tan_half_fov_y / height};
    values["grid_morph_start"] = {grid.morph_start};
    values["grid_morph_end"] = {grid.morph_end};
    return values;
}

RenderJob mesh_render_job(const LanguageBuild& lang, const SyntheticScene& scene,
                          const MeshData& mesh,
                          const std::map<std::string, std::vector<double>>& values, uint32_t width,
                          uint32_t height, uint32_t timed_draws) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.timed_draws = timed_draws;
    // Every stage declares the one block (build_shader): the fragment's layout is all of them.
    RenderJob job = scene_inputs_job(lang, scene, settings, &values);
    if (const auto it = scene.textures.find("scene_color"); it != scene.textures.end())
        job.background = it->second.rgba;
    job.mesh = mesh;
    if (lang.tessellated()) {
        job.tess_control_spirv = lang.control.toolchain.spirv_optimized;
        job.tess_evaluation_spirv = lang.evaluation.toolchain.spirv_optimized;
        job.tess_control_reflection = lang.control.toolchain.reflection;
        job.tess_evaluation_reflection = lang.evaluation.toolchain.reflection;
    }
    return job;
}

MeshRender render_mesh_variant(VulkanRunner& runner, const VariantBuild& build,
                               const SyntheticScene& scene, const MeshRenderSettings& settings) {
    MeshRender out;
    if (!build.ok()) {
        out.error = "variant did not build";
        return out;
    }
    if (!build.shader.mesh) {
        out.error = "a screen-pass variant has no mesh to draw (geometry=mesh or tessellated)";
        return out;
    }
    if (auto why = water_grid_error(settings.grid)) {
        out.error = *why;
        return out;
    }
    if (scene.width != settings.width || scene.height != settings.height) {
        out.error = "scene size differs from the render size";
        return out;
    }
    const WaterGrid grid = scene_grid(scene, settings.grid, build.shader.mesh->tessellated(),
                                      settings.width, settings.height);
    const MeshData mesh = grid_mesh(grid);
    out.vertices = grid.vertex_count();
    out.primitives = grid_primitives(grid);
    std::map<std::string, std::vector<double>> values =
        mesh_values(scene, grid, settings.width, settings.height);
    for (const auto& [name, value] : settings.overrides)
        values[name] = value;
    runner.clear_validation_messages();
    for (size_t i = 0; i < 2; ++i) {
        RenderJob job = mesh_render_job(build.languages[i], scene, mesh, values, settings.width,
                                        settings.height, settings.timed_draws);
        job.cull_back_faces = settings.cull_back_faces;
        out.gpu[i] = runner.render(job);
        if (!out.gpu[i].ok) {
            out.error =
                std::string(to_string(build.languages[i].language)) + " path: " + out.gpu[i].error;
            return out;
        }
        out.gpu_image[i] = ImageRGBA32F{settings.width, settings.height, out.gpu[i].rgba};
    }
    for (size_t p = 0; p < out.gpu[0].rgba.size() / 4; ++p)
        out.covered += out.gpu[0].rgba[p * 4 + 3] != 0.0f;
    out.validation_messages = runner.validation_messages();
    out.glsl_vs_hlsl = compare_images(out.gpu_image[0], out.gpu_image[1]);
    return out;
}

Variant screen_pass_of(const Variant& mesh_variant) {
    Variant v = mesh_variant;
    set_choice(v, "geometry", "screen_pass");
    return v;
}

Graph exact_surface_fragment(const Material& material, const ScenePlan* plan,
                             const Variant& mesh_variant) {
    WaterShader surface = material.compose(screen_pass_of(mesh_variant), SurfaceSearch::Converged);
    if (plan) surface.fragment = fold_graph(surface.fragment, plan->facts).graph;
    return surface.fragment;
}

VariantRender render_mesh_against_surface(VulkanRunner& runner, const VariantBuild& build,
                                          const SyntheticScene& scene,
                                          const RenderSettings& settings) {
    VariantRender out;
    out.key = build.shader.variant.key();
    out.against_surface = true;
    MeshRenderSettings mesh{settings.width, settings.height, settings.grid, settings.timed_draws};
    MeshRender drawn = render_mesh_variant(runner, build, scene, mesh);
    if (!drawn.ok()) {
        out.error = drawn.error;
        return out;
    }
    out.gpu = std::move(drawn.gpu);
    out.gpu_image = std::move(drawn.gpu_image);
    out.glsl_vs_hlsl = drawn.glsl_vs_hlsl;
    out.validation_messages = std::move(drawn.validation_messages);
    if (!settings.cpu_float && !settings.cpu_double) return out;
    const Graph surface = exact_surface_fragment(preset_material(find_preset(build.shader.preset)),
                                                 nullptr, build.shader.variant);
    auto evaluate = [&](EvalPrecision precision, ImageRGBA32F& image) {
        const EvalResult r = evaluate_image(surface, "color", scene.eval_inputs(), settings.width,
                                            settings.height, precision);
        if (!r.ok()) out.error = "CPU evaluator: " + r.error;
        image = to_image(r, settings.width, settings.height);
        return r.ok();
    };
    if (settings.cpu_float) {
        if (!evaluate(EvalPrecision::Float, out.cpu_float)) return out;
        out.glsl_vs_cpu_float = compare_images(out.gpu_image[0], out.cpu_float);
        out.hlsl_vs_cpu_float = compare_images(out.gpu_image[1], out.cpu_float);
    }
    if (settings.cpu_double) {
        if (!evaluate(EvalPrecision::Double, out.cpu_double)) return out;
        out.glsl_vs_cpu_double = compare_images(out.gpu_image[0], out.cpu_double);
    }
    return out;
}

} // namespace watergen
