// Per-pixel error maps between a variant's image and its reference, the figures a comparison
// table needs beyond compare_images, and where to look: the window of the highest mean error,
// cropped and zoomed.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "watergen/eval/image/flip.h"
#include "watergen/eval/image/image_io.h"
#include "watergen/eval/image/image_metrics.h"

namespace watergen {

// CIEDE2000 of about 2.3 is a just noticeable difference (Sharma, "Digital Color Imaging
// Handbook", 2003; Mahy et al. 1994 give 2.3 for CIELAB).
constexpr double kJustNoticeableDeltaE = 2.3;
// In the window search a non-finite pixel weighs as dE 100 (black against white), so broken
// pixels draw the window to them.
constexpr double kNonFiniteDeltaEWeight = 100.0;

// A rectangle of pixels; x, y = top-left corner.
struct PixelRegion {
    uint32_t x = 0, y = 0, width = 0, height = 0;
};

struct ErrorMaps {
    std::string error;     // non-empty: the images could not be compared; the rest is empty
    ImageErrorStats stats; // compare_images(test, reference, exposure)
    uint32_t width = 0, height = 0;
    // ciede2000_map(test, reference, exposure) as float: NaN where either side is non-finite.
    std::vector<float> ciede2000;
    FlipMap flip; // flip_linear(reference, test, exposure, pixels_per_degree)
    // Share of compared pixels (finite on both sides) with dE00 > kJustNoticeableDeltaE, in
    // [0, 1]; NaN if no pixel could be compared.
    double share_above_jnd = 0;
    // worst_region(ciede2000, ..., default_window_size(width, height)).
    PixelRegion worst;

    bool ok() const noexcept { return error.empty(); }
};

// Everything above for one image against its reference, both tone-mapped with `exposure`.
ErrorMaps compute_error_maps(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                             float exposure = 1.0f,
                             double pixels_per_degree = kFlipDefaultPixelsPerDegree);

// The side of the square window for worst_region: min(width, height) / 8, within [1, 32].
uint32_t default_window_size(uint32_t width, uint32_t height);

// The window x window square (clipped to the image when it is smaller) with the highest mean
// value, by a summed-area table over all positions; ties go to the first in row-major order.
// Non-finite values count as `non_finite_weight`. Empty region if values.size() != width *
// height or the image is empty.
PixelRegion worst_region(std::span<const float> values, uint32_t width, uint32_t height,
                         uint32_t window, double non_finite_weight = kNonFiniteDeltaEWeight);

// `region` grown by `margin` pixels on every side, clipped to a width x height image (the context
// around a worst window).
PixelRegion grown_region(PixelRegion region, uint32_t margin, uint32_t width, uint32_t height);

// The part of `image` inside `region` (clipped to the image; empty if nothing is left).
ImageRGBA8 crop(const ImageRGBA8& image, PixelRegion region);

// Each pixel becomes a factor x factor block (nearest neighbour); factor 0 gives an empty image.
ImageRGBA8 zoom_nearest(const ImageRGBA8& image, uint32_t factor);

// Draws the 1-pixel border of `region` (clipped to the image) in `rgb`, opaque.
void outline_region(ImageRGBA8& image, PixelRegion region, std::array<uint8_t, 3> rgb);

} // namespace watergen
