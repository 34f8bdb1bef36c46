#include "watergen/eval/scene/synthetic_scene.h"
#include "watergen/water/nodes/foam.h"

namespace watergen {

void add_foam_inputs(SyntheticScene& scene) {
    // One period over n - 1 texels: texel n - 1 equals texel 0 (see nodes/foam.h).
    const uint32_t n = kFoamPatternSize;
    TextureData pattern{n, n, 1, std::vector<float>(size_t(n) * n * 4)};
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
            const float value =
                static_cast<float>(foam_pattern_value(double(x) / (n - 1), double(y) / (n - 1)));
            const size_t i = (size_t(y) * n + x) * 4;
            pattern.rgba[i + 0] = pattern.rgba[i + 1] = pattern.rgba[i + 2] = value;
            pattern.rgba[i + 3] = 1.0f;
        }
    scene.textures[foam_pattern_texture().name] = std::move(pattern);
}

} // namespace watergen
