#include "watergen/eval/draw/tessellated_mesh_render.h"

#include "watergen/ir/specialization.h"
#include "watergen/ir/uniform_layout.h"

namespace watergen {

MeshData make_patches(uint32_t n, double x0, double x1, double z0, double z1) {
    MeshData mesh = make_grid(n, x0, x1, z0, z1); // the same points, in the same order
    mesh.indices.clear();
    mesh.patch_control_points = 4;
    for (uint32_t j = n < 2 ? 0 : n - 1; j-- > 0;) // far rows (large z) first
        for (uint32_t i = 0; i + 1 < n; ++i) {
            const uint32_t a = j * n + i;
            mesh.indices.insert(mesh.indices.end(), {a, a + 1, a + n, a + n + 1});
        }
    return mesh;
}

RenderJob tessellated_mesh_job(const TessellatedLanguageBuild& lang, const MeshData& patches,
                               uint32_t width, uint32_t height,
                               const std::map<std::string, std::vector<double>>& values,
                               uint32_t timed_draws) {
    // Both patch stages declare the one block (and the same specialization constants).
    RenderJob job = geometry_job(lang.vertex, lang.fragment, lang.evaluation.source.interface,
                                 patches, width, height, values, timed_draws);
    job.tess_control_spirv = lang.control.toolchain.spirv_optimized;
    job.tess_evaluation_spirv = lang.evaluation.toolchain.spirv_optimized;
    job.tess_control_reflection = lang.control.toolchain.reflection;
    job.tess_evaluation_reflection = lang.evaluation.toolchain.reflection;
    return job;
}

MeshRender render_tessellated_mesh(VulkanRunner& runner, const TessellatedMeshBuild& build,
                                   const SyntheticScene& scene, const MeshRenderSettings& settings,
                                   const std::map<std::string, std::vector<double>>& overrides) {
    MeshRender out;
    if (!build.ok()) {
        out.error = "tessellated mesh did not build";
        return out;
    }
    std::map<std::string, std::vector<double>> values = mesh_values(scene, settings);
    for (const auto& [name, value] : overrides)
        values[name] = value;
    const MeshData patches =
        make_patches(settings.grid, settings.x0, settings.x1, settings.z0, settings.z1);
    std::array<RenderJob, 2> jobs;
    for (size_t i = 0; i < 2; ++i) {
        jobs[i] = tessellated_mesh_job(build.languages[i], patches, settings.width, settings.height,
                                       values, settings.timed_draws);
        jobs[i].cull_back_faces = settings.cull_back_faces;
    }
    return render_language_pair(runner, jobs, settings);
}

} // namespace watergen
