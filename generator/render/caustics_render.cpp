#include "watergen/render/caustics_render.h"

#include <algorithm>
#include <cmath>

#include "watergen/render/mesh_render.h"

namespace watergen {

namespace {

const std::vector<double>& value(const std::map<std::string, std::vector<double>>& values,
                                 const std::string& name) {
    static const std::vector<double> none;
    auto it = values.find(name);
    return it == values.end() ? none : it->second;
}

double scalar(const std::map<std::string, std::vector<double>>& values, const std::string& name,
              double fallback) {
    const auto& v = value(values, name);
    return v.empty() ? fallback : v[0];
}

} // namespace

CausticsBuild build_caustics(CausticsMethod method, const std::string& wave_model) {
    CausticsBuild b{build_caustics_pass(method, wave_model), {}, {}};
    const std::string name = std::string("caustics_") + to_string(method) + "_" + wave_model;
    b.languages = build_two_stages(b.pass.vertex, b.pass.fragment, caustics_skeleton(method), name,
                                   std::string("caustics.") + to_string(method) + "." + wave_model,
                                   b.diagnostics);
    return b;
}

std::map<std::string, std::vector<double>>
caustics_values(const CausticsBuild& build,
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

RenderJob caustics_job(const CausticsBuild& build, size_t language,
                       const std::map<std::string, std::vector<double>>& values,
                       const CausticsRenderSettings& settings, std::string* error) {
    const std::vector<double>& window = value(values, "caustics_window");
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
    MeshData grid =
        make_grid(photons ? cells : cells + 1, x0 + h, x0 + extent - h, z0 + h, z0 + extent - h);
    std::map<std::string, std::vector<double>> drawn = values;
    if (photons) {
        grid.points = true;
        grid.indices.resize(grid.vertices.size() / 2);
        for (uint32_t i = 0; i < grid.indices.size(); ++i)
            grid.indices[i] = i;
        const double share = 1.0 / (double(settings.cells_per_texel) * settings.cells_per_texel);
        drawn["caustics_photon_share"] = {share};
    }
    RenderJob job = mesh_job(build.languages[language], grid, settings.texels, settings.texels,
                             drawn, settings.timed_draws);
    job.additive_blend = true;
    return job;
}

CausticsRender render_caustics(VulkanRunner& runner, const CausticsBuild& build,
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

CausticsSetup caustics_reference_setup(const std::string& model,
                                       const std::map<std::string, std::vector<double>>& values,
                                       uint32_t texels, double margin) {
    CausticsSetup s;
    const std::string f = model == "gerstner" ? "gerstner" : "waves";
    const int count = std::clamp(int(std::floor(scalar(values, f + "_wave_count", 0))), 0, 8);
    const double time = scalar(values, "time", 0);
    const std::vector<double>& directions = value(values, f + "_wave_directions");
    const std::vector<double>& speeds = value(values, f + "_wave_speeds");
    double a = scalar(values, f + "_amplitude", 0), w = scalar(values, f + "_frequency", 1);
    const double ga = scalar(values, f + "_amplitude_gain", 1);
    const double gf = scalar(values, f + "_frequency_gain", 1);
    const double q = scalar(values, "gerstner_steepness", 0);
    for (int i = 0; i < count && size_t(2 * i + 1) < directions.size() && size_t(i) < speeds.size();
         ++i) {
        CausticsWave wave;
        wave.amplitude = a;
        wave.frequency = w;
        wave.dir_x = directions[size_t(2 * i)];
        wave.dir_z = directions[size_t(2 * i + 1)];
        wave.phase = time * speeds[size_t(i)];
        // GPU Gems' Q_i = Q / (w_i A_i n) (the shader guards w_i A_i from 0 the same way).
        if (model == "gerstner") wave.steepness = q / (count * std::max(w * a, 1e-6));
        s.waves.push_back(wave);
        a *= ga;
        w *= gf;
    }
    const std::vector<double>& sun = value(values, "sun_direction");
    if (sun.size() == 3) s.sun_direction = {sun[0], sun[1], sun[2]};
    s.ior = scalar(values, "ior_water", 1.33333);
    s.depth = scalar(values, "caustics_depth", 5);
    const std::vector<double>& window = value(values, "caustics_window");
    if (window.size() == 3) {
        s.x0 = window[0];
        s.z0 = window[1];
        s.size = window[2];
    }
    s.texels = texels;
    s.periodic = false;
    s.margin = margin;
    return s;
}

} // namespace watergen
