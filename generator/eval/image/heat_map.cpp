#include "watergen/eval/image/heat_map.h"

#include <algorithm>
#include <cmath>

namespace watergen {

namespace {

// matplotlib's magma (van der Walt and Smith, 2015) at t = 0, 1/8, ..., 1, 8-bit sRGB.
constexpr std::array<std::array<uint8_t, 3>, 9> kMagmaSamples{{
    {0, 0, 4},
    {28, 16, 68},
    {81, 18, 124},
    {131, 38, 129},
    {183, 55, 121},
    {231, 82, 99},
    {252, 137, 97},
    {254, 196, 136},
    {252, 253, 191},
}};

void put_pixel(ImageRGBA8& image, std::size_t pixel, std::array<uint8_t, 3> rgb) {
    uint8_t* px = &image.rgba[pixel * 4];
    px[0] = rgb[0];
    px[1] = rgb[1];
    px[2] = rgb[2];
    px[3] = 255;
}

} // namespace

HeatScale ciede2000_scale() {
    return HeatScale{"CIEDE2000", 0.0, 10.0, {0.0, 2.3, 5.0, 10.0}};
}

HeatScale flip_scale() {
    return HeatScale{"FLIP", 0.0, 1.0, {0.0, 0.25, 0.5, 0.75, 1.0}};
}

std::array<uint8_t, 3> magma(double t) {
    if (!(t > 0.0)) return kMagmaSamples.front(); // also NaN
    if (t >= 1.0) return kMagmaSamples.back();
    const double position = t * double(kMagmaSamples.size() - 1);
    const std::size_t i = static_cast<std::size_t>(position);
    const double f = position - double(i);
    std::array<uint8_t, 3> out{};
    for (int c = 0; c < 3; ++c) {
        const double v = kMagmaSamples[i][c] + f * (kMagmaSamples[i + 1][c] - kMagmaSamples[i][c]);
        out[c] = static_cast<uint8_t>(std::lround(v));
    }
    return out;
}

double scale_position(const HeatScale& scale, double value) {
    if (!(scale.hi > scale.lo)) return 0.0;
    return std::clamp((value - scale.lo) / (scale.hi - scale.lo), 0.0, 1.0);
}

ImageRGBA8 heat_map(std::span<const float> values, uint32_t width, uint32_t height,
                    const HeatScale& scale) {
    ImageRGBA8 image{width, height, {}};
    if (values.size() != image.pixel_count()) return ImageRGBA8{};
    image.rgba.resize(image.pixel_count() * 4);
    for (std::size_t p = 0; p < values.size(); ++p) {
        const bool finite = std::isfinite(values[p]);
        put_pixel(image, p, finite ? magma(scale_position(scale, values[p])) : kHeatNonFiniteColor);
    }
    return image;
}

ImageRGBA8 color_bar(const HeatScale& scale, uint32_t width, uint32_t height) {
    ImageRGBA8 image{width, height, std::vector<uint8_t>(std::size_t{width} * height * 4)};
    for (uint32_t x = 0; x < width; ++x) {
        const double t = width > 1 ? double(x) / double(width - 1) : 0.0;
        const std::array<uint8_t, 3> rgb =
            magma(scale_position(scale, scale.lo + (scale.hi - scale.lo) * t));
        for (uint32_t y = 0; y < height; ++y)
            put_pixel(image, std::size_t{y} * width + x, rgb);
    }
    return image;
}

} // namespace watergen
