// The synthetic scene's caustics textures (caustics axis, nodes/caustics.h): a periodic tile
// and the map over the caustics window, both from the CPU photon reference, so the GPU and the
// CPU evaluator sample the same data.
#include <cmath>
#include <map>

#include "watergen/caustics/caustics_pass.h"
#include "watergen/caustics/caustics_reference.h"
#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/nodes/caustics.h"

namespace watergen {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// Texels per side of both textures (the nodes' caustics_tile_texels and caustics_map_texels
// defaults) and photons per texel side: 64 x 64 x 9 photons, a few ms each, since
// make_synthetic_scene runs for every render. Regular photon grids over smooth waves give a
// smooth estimate, so the GPU and the CPU sampling it a float ulp apart agree.
constexpr uint32_t kTexels = kSceneCausticsTexels;
constexpr uint32_t kPhotonsPerSide = 3;

TextureData intensity_texture(uint32_t texels, auto&& value) {
    std::vector<double> intensity(size_t(texels) * texels);
    for (uint32_t j = 0; j < texels; ++j)
        for (uint32_t i = 0; i < texels; ++i)
            intensity[size_t(j) * texels + i] = value(i, j);
    return caustics_texture(intensity, texels);
}

// Crest's stand-in tile: three waves periodic over the 10 m tile (integer cycles per tile),
// sun straight down, 2 m deep: below the focal depth, so the intensity stays within about
// [0.6, 1.6]. The reference covers n - 1 texels centred on k / (n - 1); texel n - 1 repeats
// texel 0, the layout tile_coordinate() reads.
TextureData make_caustics_tile() {
    const double size = 10.0;
    CausticsSetup s;
    const struct {
        double amplitude, m, n, phase;
    } kWaves[] = {{0.06, 1, 2, 0.3}, {0.05, 3, -1, 1.7}, {0.04, 2, 3, 4.1}};
    for (const auto& w : kWaves) {
        const double cycles = std::hypot(w.m, w.n);
        s.waves.push_back(
            {w.amplitude, kTwoPi * cycles / size, w.m / cycles, w.n / cycles, w.phase, 0.0});
    }
    s.depth = 2.0;
    s.texels = kTexels - 1;
    s.size = size;
    s.x0 = s.z0 = -0.5 * size / s.texels;
    s.photons_per_side = kPhotonsPerSide;
    std::string error;
    const CausticsImage image = caustics_reference(s, &error);
    const uint32_t n = s.texels;
    return intensity_texture(kTexels, [&](uint32_t i, uint32_t j) {
        return image.intensity.empty() ? 1.0 : image.intensity[size_t(j % n) * n + i % n];
    });
}

// The caustics pass's map for the scene's waves (the Gerstner defaults at the scene's time and
// sun) over the scene's window (the pass's default one, moved by the scene's world offset), at
// the scene's caustics depth and margin. The reference evaluates the waves at the window's
// absolute positions in double, so a far window gets the map of the waves there.
TextureData make_caustics_map(const SyntheticScene& scene) {
    const CausticsPass pass = build_caustics_pass(CausticsMethod::AreaRatio, "gerstner");
    std::map<std::string, std::vector<double>> values;
    for (const Parameter& p : pass.vertex.parameters())
        values[p.name] = p.default_value;
    for (const char* name : {"sun_direction", "time"})
        values[name] = scene.uniforms.at(name);
    if (auto it = scene.uniforms.find(caustics_window().name); it != scene.uniforms.end())
        values[it->first] = it->second;
    values["caustics_depth"] = {kSceneCausticsDepth};
    CausticsSetup s = caustics_reference_setup("gerstner", values, kTexels, kSceneCausticsMargin);
    s.photons_per_side = kPhotonsPerSide;
    std::string error;
    const CausticsImage image = caustics_reference(s, &error);
    return intensity_texture(kTexels, [&](uint32_t i, uint32_t j) {
        return image.intensity.empty() ? 1.0 : image.intensity[size_t(j) * kTexels + i];
    });
}

} // namespace

TextureData caustics_texture(const std::vector<double>& intensity, uint32_t texels) {
    TextureData t{texels, texels, 1, std::vector<float>(size_t(texels) * texels * 4)};
    for (size_t p = 0; p < intensity.size() && p < size_t(texels) * texels; ++p) {
        float* out = &t.rgba[p * 4];
        out[0] = out[1] = out[2] = static_cast<float>(intensity[p]);
        out[3] = 1.0f;
    }
    return t;
}

void add_caustics_inputs(SyntheticScene& scene) {
    scene.textures[caustics_tile_texture().name] = make_caustics_tile();
    scene.textures[caustics_map_texture().name] = make_caustics_map(scene);
}

} // namespace watergen
