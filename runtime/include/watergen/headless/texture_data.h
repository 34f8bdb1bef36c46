// The images a headless draw or compute job samples (headless_device.h, offscreen_draw.h,
// compute_job.h) and the filter of their sampler.
#pragma once

#include <cstdint>
#include <vector>

namespace watergen {

enum class TextureFilter { Nearest, Linear };

// RGBA32F texels, layer-major, then rows, then columns: rgba.size() == width*height*layers*4.
// Row 0 is v = 0. Cube layers are in Vulkan face order +X, -X, +Y, -Y, +Z, -Z.
struct TextureData {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t layers = 1; // 1 = 2D, 6 = cube
    std::vector<float> rgba;
};

} // namespace watergen
