#include "watergen/eval/draw/caustics_pass_draw.h"

#include <algorithm>
#include <cmath>

#include "watergen/ir/emit/specialization.h"
#include "watergen/ir/emit/uniform_layout.h"

namespace watergen {

namespace {

// n x n vertices with attribute grid_xz spanning [x0, x1] x [z0, z1], two triangles per cell.
MeshData make_grid(uint32_t n, double x0, double x1, double z0, double z1) {
    MeshData mesh;
    mesh.attribute_sizes = {2};
    if (n < 2) return mesh;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            mesh.vertices.push_back(static_cast<float>(x0 + (x1 - x0) * i / (n - 1)));
            mesh.vertices.push_back(static_cast<float>(z0 + (z1 - z0) * j / (n - 1)));
        }
    for (uint32_t j = n - 1; j-- > 0;)
        for (uint32_t i = 0; i + 1 < n; ++i) {
            const uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    return mesh;
}

// The pass's job: its vertex stage's block (the only one) packed from `values`.
RenderJob pass_job(const LanguageBuild& lang, const MeshData& mesh, uint32_t size,
                   const std::map<std::string, std::vector<double>>& values,
                   const FrameCentre& centre, uint32_t timed_draws) {
    RenderJob job;
    job.vertex_spirv = lang.vertex.toolchain.spirv_optimized;
    job.fragment_spirv = lang.fragment.toolchain.spirv_optimized;
    job.vertex_reflection = lang.vertex.toolchain.reflection;
    job.fragment_reflection = lang.fragment.toolchain.reflection;
    job.width = job.height = size;
    const ShaderInterface& block = lang.vertex.source.interface;
    job.uniforms = pack_uniforms(block.uniforms, block.parameters, values, centre);
    job.specialization = specialization_values(block.specialization, values);
    job.timed_draws = timed_draws;
    job.mesh = mesh;
    return job;
}

} // namespace

std::map<std::string, std::vector<double>>
caustics_values(const CausticsPassBuild& build,
                const std::map<std::string, std::vector<double>>& values) {
    std::map<std::string, std::vector<double>> out;
    for (const Parameter& p : build.languages[0].vertex.source.interface.parameters)
        out[p.name] = p.default_value;
    for (const auto& [name, v] : values)
        out[name] = v;
    return out;
}

uint32_t default_cells_per_texel(CausticsMethod method) {
    return method == CausticsMethod::PhotonSplat ? 8 : 2;
}

RenderJob caustics_job(const CausticsPassBuild& build, size_t language,
                       const std::map<std::string, std::vector<double>>& values,
                       const CausticsRenderSettings& settings, std::string* error) {
    const auto window_value = values.find("caustics_window");
    const std::vector<double> window =
        window_value == values.end() ? std::vector<double>{} : window_value->second;
    if (window.size() != 3 || !(window[2] > 0)) {
        *error = "caustics_window must be (x0, z0, size) with size > 0";
        return {};
    }
    const double texel = window[2] / settings.texels;
    const uint32_t margin_texels = uint32_t(std::ceil(settings.margin / texel));
    const uint32_t cells = (settings.texels + 2 * margin_texels) * settings.cells_per_texel;
    const double x0 = window[0] - margin_texels * texel, z0 = window[1] - margin_texels * texel;
    const double extent = cells * texel / settings.cells_per_texel;
    const bool photons = build.pass.method == CausticsMethod::PhotonSplat;
    // Triangles: cells + 1 vertices per side spanning the area. Photons: one at each cell's
    // centre, so that under flat water no photon lies on a texel's edge and every texel
    // catches exactly cells_per_texel^2 of them.
    const double h = photons ? extent / cells / 2 : 0;
    // The pass works in the frame of the window's corner (runtime/host_values.h): its grid
    // and its window relative to that centre, its wave phases reduced there, so the map is as
    // exact 1,000 km from the world origin as at it.
    const FrameCentre c = frame_centre_of(window[0], window[1]);
    MeshData grid = make_grid(photons ? cells : cells + 1, x0 + h - c.x, x0 + extent - h - c.x,
                              z0 + h - c.z, z0 + extent - h - c.z);
    std::map<std::string, std::vector<double>> drawn = values;
    if (photons) {
        grid.points = true;
        grid.indices.resize(grid.vertices.size() / 2);
        for (uint32_t i = 0; i < grid.indices.size(); ++i)
            grid.indices[i] = i;
        const double share = 1.0 / (double(settings.cells_per_texel) * settings.cells_per_texel);
        drawn["caustics_photon_share"] = {share};
    }
    RenderJob job =
        pass_job(build.languages[language], grid, settings.texels, drawn, c, settings.timed_draws);
    job.additive_blend = true;
    return job;
}

CausticsRender render_caustics(VulkanRunner& runner, const CausticsPassBuild& build,
                               const std::map<std::string, std::vector<double>>& values,
                               const CausticsRenderSettings& settings) {
    CausticsRender out;
    if (!build.ok()) {
        out.error = "caustics pass did not build";
        return out;
    }
    for (size_t i = 0; i < 2; ++i) {
        const RenderJob job = caustics_job(build, i, values, settings, &out.error);
        if (!out.ok()) return out;
        out.gpu[i] = runner.render(job);
        if (!out.gpu[i].ok) {
            out.error =
                std::string(to_string(build.languages[i].language)) + " path: " + out.gpu[i].error;
            return out;
        }
        auto& intensity = out.intensity[i];
        for (size_t p = 0; p < out.gpu[i].rgba.size(); p += 4)
            intensity.push_back(out.gpu[i].rgba[p]);
    }
    out.glsl_vs_hlsl =
        compare_images(ImageRGBA32F{settings.texels, settings.texels, out.gpu[0].rgba},
                       ImageRGBA32F{settings.texels, settings.texels, out.gpu[1].rgba});
    return out;
}

CausticsError caustics_error(const std::vector<double>& pass,
                             const std::vector<double>& reference) {
    CausticsError e;
    if (pass.empty() || pass.size() != reference.size()) return e;
    double sq = 0, sum = 0;
    for (size_t i = 0; i < pass.size(); ++i) {
        const double d = pass[i] - reference[i];
        e.max_abs = std::max(e.max_abs, std::abs(d));
        sq += d * d;
        sum += d;
    }
    e.rmse = std::sqrt(sq / double(pass.size()));
    e.mean_difference = sum / double(pass.size());
    return e;
}

ImageRGBA8 caustics_image(const std::vector<double>& intensity, uint32_t texels) {
    ImageRGBA32F image{texels, texels, {}};
    for (double v : intensity)
        image.rgba.insert(image.rgba.end(), {float(v), float(v), float(v), 1.0f});
    return {texels, texels, tone_map_to_srgb8(image, 0.25f)};
}

} // namespace watergen
