#include "watergen/eval/draw/mesh_render.h"

#include "watergen/ir/specialization.h"
#include "watergen/ir/uniform_layout.h"

namespace watergen {

RenderJob geometry_job(const StageBuild& vertex, const StageBuild& fragment,
                       const ShaderInterface& block, const MeshData& mesh, uint32_t width,
                       uint32_t height, const std::map<std::string, std::vector<double>>& values,
                       uint32_t timed_draws) {
    RenderJob job;
    job.vertex_spirv = vertex.toolchain.spirv_optimized;
    job.fragment_spirv = fragment.toolchain.spirv_optimized;
    job.vertex_reflection = vertex.toolchain.reflection;
    job.fragment_reflection = fragment.toolchain.reflection;
    job.width = width;
    job.height = height;
    job.uniforms = pack_uniforms(block.uniforms, block.parameters, values);
    job.specialization = specialization_values(block.specialization, values);
    job.timed_draws = timed_draws;
    job.mesh = mesh;
    return job;
}

RenderJob mesh_job(const LanguageBuild& lang, const MeshData& mesh, uint32_t width, uint32_t height,
                   const std::map<std::string, std::vector<double>>& values, uint32_t timed_draws) {
    return geometry_job(lang.vertex, lang.fragment, lang.vertex.source.interface, mesh, width,
                        height, values, timed_draws);
}

MeshBuild build_mesh(const std::string& wave_model) {
    MeshBuild b{build_mesh_shader(wave_model), {}, {}};
    b.languages = build_two_stages(b.shader.vertex, b.shader.fragment, "mesh", "mesh_" + wave_model,
                                   "mesh." + wave_model, b.diagnostics);
    return b;
}

MeshData make_grid(uint32_t n, double x0, double x1, double z0, double z1) {
    MeshData mesh;
    mesh.attribute_sizes = {2};
    if (n < 2) return mesh;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            mesh.vertices.push_back(static_cast<float>(x0 + (x1 - x0) * i / (n - 1)));
            mesh.vertices.push_back(static_cast<float>(z0 + (z1 - z0) * j / (n - 1)));
        }
    for (uint32_t j = n - 1; j-- > 0;) // far rows (large z) first
        for (uint32_t i = 0; i + 1 < n; ++i) {
            const uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    return mesh;
}

std::map<std::string, std::vector<double>> mesh_values(const SyntheticScene& scene,
                                                       const MeshRenderSettings& settings) {
    const SceneCamera cam = scene_camera(settings.width, settings.height);
    std::map<std::string, std::vector<double>> values = scene.uniforms;
    values["mesh_camera_right"] = {cam.right[0], cam.right[1], cam.right[2]};
    values["mesh_camera_up"] = {cam.up[0], cam.up[1], cam.up[2]};
    values["mesh_camera_forward"] = {cam.forward[0], cam.forward[1], cam.forward[2]};
    values["mesh_projection"] = {1.0 / (cam.tan_half_fov_y * cam.aspect), 1.0 / cam.tan_half_fov_y};
    values["eye_position"] = {cam.eye[0], cam.eye[1], cam.eye[2]};
    return values;
}

MeshRender render_mesh(VulkanRunner& runner, const MeshBuild& build, const SyntheticScene& scene,
                       const MeshRenderSettings& settings) {
    MeshRender out;
    if (!build.ok()) {
        out.error = "mesh did not build";
        return out;
    }
    const std::map<std::string, std::vector<double>> values = mesh_values(scene, settings);
    const MeshData grid =
        make_grid(settings.grid, settings.x0, settings.x1, settings.z0, settings.z1);
    std::array<RenderJob, 2> jobs;
    for (size_t i = 0; i < 2; ++i) {
        jobs[i] = mesh_job(build.languages[i], grid, settings.width, settings.height, values,
                           settings.timed_draws);
        jobs[i].cull_back_faces = settings.cull_back_faces;
    }
    return render_language_pair(runner, jobs, settings);
}

MeshRender render_language_pair(VulkanRunner& runner, const std::array<RenderJob, 2>& jobs,
                                const MeshRenderSettings& settings) {
    MeshRender out;
    runner.clear_validation_messages();
    for (size_t i = 0; i < 2; ++i) {
        out.gpu[i] = runner.render(jobs[i]);
        if (!out.gpu[i].ok) {
            out.error = std::string(i == 0 ? "glsl" : "hlsl") + " path: " + out.gpu[i].error;
            return out;
        }
        out.gpu_image[i] = ImageRGBA32F{settings.width, settings.height, out.gpu[i].rgba};
    }
    out.validation_messages = runner.validation_messages();
    out.glsl_vs_hlsl = compare_images(out.gpu_image[0], out.gpu_image[1]);
    return out;
}

} // namespace watergen
