#include "watergen/eval/image/error_maps.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace watergen {

namespace {

// Clips `region` to a width x height image.
PixelRegion clipped(PixelRegion r, uint32_t width, uint32_t height) {
    if (r.x >= width || r.y >= height) return PixelRegion{};
    r.width = std::min(r.width, width - r.x);
    r.height = std::min(r.height, height - r.y);
    return r;
}

} // namespace

ErrorMaps compute_error_maps(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                             float exposure, double pixels_per_degree) {
    ErrorMaps m;
    m.stats = compare_images(test, reference, exposure);
    if (!m.stats.ok()) {
        m.error = m.stats.error;
        return m;
    }
    m.flip = flip_linear(reference, test, exposure, pixels_per_degree);
    if (!m.flip.ok()) {
        m.error = m.flip.error;
        return m;
    }
    m.width = test.width;
    m.height = test.height;
    const std::vector<double> delta_e = ciede2000_map(test, reference, exposure);
    m.ciede2000.assign(delta_e.begin(), delta_e.end());
    uint64_t above = 0;
    for (double e : delta_e)
        above += e > kJustNoticeableDeltaE ? 1 : 0; // NaN compares false
    m.share_above_jnd = m.stats.compared_pixels == 0
                            ? std::numeric_limits<double>::quiet_NaN()
                            : double(above) / double(m.stats.compared_pixels);
    m.worst = worst_region(m.ciede2000, m.width, m.height, default_window_size(m.width, m.height));
    return m;
}

uint32_t default_window_size(uint32_t width, uint32_t height) {
    return std::clamp(std::min(width, height) / 8, 1u, 32u);
}

PixelRegion worst_region(std::span<const float> values, uint32_t width, uint32_t height,
                         uint32_t window, double non_finite_weight) {
    if (width == 0 || height == 0 || values.size() != std::size_t{width} * height || window == 0)
        return PixelRegion{};
    const uint32_t kw = std::min(window, width), kh = std::min(window, height);
    // sat[(y) * (width + 1) + x] = sum of values[0..y) x [0..x).
    const std::size_t stride = std::size_t{width} + 1;
    std::vector<double> sat(stride * (std::size_t{height} + 1), 0.0);
    for (uint32_t y = 0; y < height; ++y) {
        double row = 0.0;
        for (uint32_t x = 0; x < width; ++x) {
            const float v = values[std::size_t{y} * width + x];
            row += std::isfinite(v) ? double(v) : non_finite_weight;
            sat[(y + 1) * stride + x + 1] = sat[y * stride + x + 1] + row;
        }
    }
    PixelRegion best{0, 0, kw, kh};
    double best_sum = -std::numeric_limits<double>::infinity();
    for (uint32_t y = 0; y + kh <= height; ++y) {
        for (uint32_t x = 0; x + kw <= width; ++x) {
            const double sum = sat[(y + kh) * stride + x + kw] - sat[y * stride + x + kw] -
                               sat[(y + kh) * stride + x] + sat[y * stride + x];
            if (sum > best_sum) {
                best_sum = sum;
                best.x = x;
                best.y = y;
            }
        }
    }
    return best;
}

PixelRegion grown_region(PixelRegion region, uint32_t margin, uint32_t width, uint32_t height) {
    const uint32_t x = region.x > margin ? region.x - margin : 0;
    const uint32_t y = region.y > margin ? region.y - margin : 0;
    const uint64_t right = uint64_t{region.x} + region.width + margin;
    const uint64_t bottom = uint64_t{region.y} + region.height + margin;
    return clipped(PixelRegion{x, y, uint32_t(std::min<uint64_t>(right, width) - x),
                               uint32_t(std::min<uint64_t>(bottom, height) - y)},
                   width, height);
}

ImageRGBA8 crop(const ImageRGBA8& image, PixelRegion region) {
    const PixelRegion r = clipped(region, image.width, image.height);
    ImageRGBA8 out{r.width, r.height, std::vector<uint8_t>(std::size_t{r.width} * r.height * 4)};
    for (uint32_t y = 0; y < r.height; ++y) {
        const auto row = image.rgba.begin() + static_cast<std::ptrdiff_t>(
                                                  (std::size_t{r.y + y} * image.width + r.x) * 4);
        std::copy(row, row + std::ptrdiff_t{r.width} * 4,
                  out.rgba.begin() + static_cast<std::ptrdiff_t>(std::size_t{y} * r.width * 4));
    }
    return out;
}

ImageRGBA8 zoom_nearest(const ImageRGBA8& image, uint32_t factor) {
    if (factor == 0) return ImageRGBA8{};
    ImageRGBA8 out{image.width * factor, image.height * factor, {}};
    out.rgba.resize(out.pixel_count() * 4);
    for (uint32_t y = 0; y < out.height; ++y) {
        for (uint32_t x = 0; x < out.width; ++x) {
            const uint8_t* src =
                &image.rgba[(std::size_t{y / factor} * image.width + x / factor) * 4];
            std::copy(src, src + 4, &out.rgba[(std::size_t{y} * out.width + x) * 4]);
        }
    }
    return out;
}

void outline_region(ImageRGBA8& image, PixelRegion region, std::array<uint8_t, 3> rgb) {
    const PixelRegion r = clipped(region, image.width, image.height);
    if (r.width == 0 || r.height == 0) return;
    auto paint = [&](uint32_t x, uint32_t y) {
        uint8_t* px = &image.rgba[(std::size_t{y} * image.width + x) * 4];
        px[0] = rgb[0];
        px[1] = rgb[1];
        px[2] = rgb[2];
        px[3] = 255;
    };
    for (uint32_t x = r.x; x < r.x + r.width; ++x) {
        paint(x, r.y);
        paint(x, r.y + r.height - 1);
    }
    for (uint32_t y = r.y; y < r.y + r.height; ++y) {
        paint(r.x, y);
        paint(r.x + r.width - 1, y);
    }
}

} // namespace watergen
