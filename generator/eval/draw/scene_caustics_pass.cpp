#include "watergen/eval/draw/scene_caustics_pass.h"

#include <algorithm>
#include <cmath>

#include "watergen/water/nodes/caustics.h"

namespace watergen {

uint32_t scene_caustics_texels(const VariantBuild& water, const SyntheticScene& scene) {
    const std::string name = "caustics_map_texels";
    std::vector<double> texels;
    for (const Parameter& p : water.languages[0].fragment.source.interface.parameters)
        if (p.name == name) texels = p.default_value;
    if (auto it = scene.uniforms.find(name); it != scene.uniforms.end()) texels = it->second;
    // The parameter's own range is [1, 16384]; a pass needs a few texels and fits in memory.
    if (texels.empty() || !std::isfinite(texels[0])) return kSceneCausticsTexels;
    return uint32_t(std::clamp(std::lround(texels[0]), 4l, 4096l));
}

std::map<std::string, std::vector<double>> scene_caustics_values(const CausticsPassBuild& build,
                                                                 const SyntheticScene& scene) {
    auto values = caustics_values(build, scene.uniforms);
    values["caustics_depth"] = {kSceneCausticsDepth};
    return values;
}

CausticsRenderSettings scene_caustics_settings(CausticsMethod method, uint32_t texels,
                                               uint32_t timed_draws) {
    CausticsRenderSettings settings;
    settings.texels = texels;
    settings.margin = kSceneCausticsMargin;
    settings.cells_per_texel = default_cells_per_texel(method);
    settings.timed_draws = timed_draws;
    return settings;
}

SceneCausticsPass draw_scene_caustics_pass(VulkanRunner& runner, const CausticsPassBuild& build,
                                           const SyntheticScene& scene, uint32_t texels,
                                           uint32_t timed_draws) {
    SceneCausticsPass out;
    out.method = build.pass.method;
    out.wave_model = build.pass.wave_model;
    out.texels = texels;
    out.diagnostics = build.diagnostics;
    const std::string name =
        std::string("caustics pass ") + to_string(out.method) + " (" + out.wave_model + " waves)";
    if (!build.ok()) {
        out.error = name + ": did not build";
        return out;
    }
    const auto values = scene_caustics_values(build, scene);
    out.window = values.at(caustics_window().name);
    const CausticsRenderSettings settings =
        scene_caustics_settings(out.method, texels, timed_draws);
    const CausticsRender r = render_caustics(runner, build, values, settings);
    if (!r.ok()) {
        out.error = name + ": " + r.error;
        return out;
    }
    CausticsSetup setup =
        caustics_reference_setup(out.wave_model, values, texels, kSceneCausticsMargin);
    setup.photons_per_side = kSceneCausticsReferencePhotons;
    const CausticsImage reference = caustics_reference(setup, &out.error);
    if (!out.ok()) {
        out.error = name + ": CPU reference: " + out.error;
        return out;
    }
    out.intensity = r.intensity[0];
    out.reference = reference.intensity;
    out.glsl = r.gpu[0];
    out.glsl.rgba.clear(); // the intensities hold what is needed
    out.vs_reference = caustics_error(out.intensity, out.reference);
    out.mean = mean_intensity(out.intensity);
    out.reference_mean = mean_intensity(out.reference);
    out.glsl_vs_hlsl = r.glsl_vs_hlsl.max_abs;
    return out;
}

void use_caustics_pass(SyntheticScene& scene, const SceneCausticsPass& pass) {
    scene.textures[caustics_map_texture().name] = caustics_texture(pass.intensity, pass.texels);
}

} // namespace watergen
