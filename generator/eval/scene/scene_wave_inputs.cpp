#include <cmath>

#include "watergen/eval/scene/scene_wave_inputs.h"
#include "watergen/eval/scene/synthetic_scene.h"

namespace watergen {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// A tile-periodic sinusoid: integer cycles (m, n) per tile along u and v.
struct Ripple {
    double weight, m, n, phase;
};

TextureData tile(uint32_t texels, auto&& texel) {
    TextureData t{texels, texels, 1, std::vector<float>(size_t(texels) * texels * 4)};
    for (uint32_t j = 0; j < texels; ++j)
        for (uint32_t i = 0; i < texels; ++i) {
            // Texel k at tile coordinate k / (n - 1): the wrap in tile_coordinate() is seamless.
            const double u = double(i) / (texels - 1), v = double(j) / (texels - 1);
            texel(u, v, &t.rgba[(size_t(j) * texels + i) * 4]);
        }
    return t;
}

} // namespace

TextureData make_height_map(uint32_t texels) {
    // Weights sum to 1, so the height stays in [-1, 1]; at most sqrt(13) cycles per tile.
    static const Ripple kRipples[] = {{0.5, 1, 2, 0.3}, {0.3, 3, -1, 1.7}, {0.2, 2, 3, 4.1}};
    return tile(texels, [](double u, double v, float* out) {
        double h = 0;
        for (const Ripple& r : kRipples)
            h += r.weight * std::sin(kTwoPi * (r.m * u + r.n * v) + r.phase);
        out[0] = static_cast<float>(h);
        out[1] = out[2] = 0.0f;
        out[3] = 1.0f;
    });
}

TextureData make_detail_normal_map(uint32_t texels) {
    // Ripple height d(u, v) with slopes up to ~0.8; n = normalize(-dd/du, -dd/dv, 1).
    static const Ripple kRipples[] = {{0.02, 3, 1, 0.9}, {0.015, -2, 4, 2.3}, {0.01, 4, 3, 5.2}};
    return tile(texels, [](double u, double v, float* out) {
        double du = 0, dv = 0;
        for (const Ripple& r : kRipples) {
            const double c = r.weight * kTwoPi * std::cos(kTwoPi * (r.m * u + r.n * v) + r.phase);
            du += c * r.m;
            dv += c * r.n;
        }
        const double len = std::sqrt(du * du + dv * dv + 1.0);
        const double n[3] = {-du / len, -dv / len, 1.0 / len};
        for (int k = 0; k < 3; ++k)
            out[k] = static_cast<float>(0.5 * n[k] + 0.5);
        out[3] = 1.0f;
    });
}

void add_wave_inputs(SyntheticScene& scene) {
    scene.textures["height_map"] = make_height_map();
    scene.textures["detail_normal_map"] = make_detail_normal_map();
    // The nodes map tiles onto texel centres with these counts (defaults, stated explicitly).
    scene.uniforms["heightmap_texels"] = {double(kWaveTextureTexels)};
    scene.uniforms["detail_texels"] = {double(kWaveTextureTexels)};
}

} // namespace watergen
