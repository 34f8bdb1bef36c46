// Error metrics between a rendered image (`test`) and the CPU reference evaluation.
#pragma once

#include <cstdint>
#include <string>

#include "watergen/runtime/image_io.h"

namespace watergen {

// CIELAB, D65 white (L in [0, 100]).
struct Lab {
    double L = 0, a = 0, b = 0;
};

// CIEDE2000 colour difference with kL = kC = kH = 1, as specified in G. Sharma, W. Wu,
// E. N. Dalal, "The CIEDE2000 color-difference formula: implementation notes, supplementary
// test data, and mathematical observations", Color Res. Appl. 30(1):21-30, 2005.
double ciede2000(Lab x, Lab y);

// 8-bit sRGB -> CIELAB: exact sRGB decoding (srgb_to_linear), the IEC 61966-2-1 linear
// sRGB -> XYZ matrix, and CIE 15 Lab with the D65 white taken as that matrix applied to
// (1, 1, 1), so every grey maps to a = b = 0.
Lab srgb8_to_lab(uint8_t r, uint8_t g, uint8_t b);

struct PixelLocation {
    uint32_t x = 0, y = 0;
};

// Alpha is ignored everywhere. "Compared" pixels are those whose RGB is finite in both images;
// all statistics except the NaN/Inf counts are over compared pixels only, so check
// nan_inf_pixels as well as the error figures.
struct ImageErrorStats {
    std::string error; // non-empty: the images could not be compared; other fields are zero

    uint64_t pixel_count = 0;              // width * height
    uint64_t compared_pixels = 0;          // pixels with finite RGB in both images
    uint64_t nan_inf_pixels = 0;           // pixels of `test` with any non-finite R, G or B
    uint64_t reference_nan_inf_pixels = 0; // the same for `reference`
    // Pixels non-finite in `test` but finite in `reference`: the tested side broke where the
    // reference did not (a failure whatever the error figures say).
    uint64_t nan_inf_where_reference_finite = 0;

    // Linear RGB differences. If no pixel could be compared (every pixel has a NaN/Inf), these
    // and the ciede2000 fields are NaN, so that any threshold check on them fails.
    double max_abs = 0;             // max over compared pixels and R, G, B of |test - ref|
    PixelLocation max_abs_location; // first such pixel in row-major order; (0, 0) if max_abs == 0
    double rmse = 0;                // sqrt(sum of squared differences / (3 * compared_pixels))
    // 10 log10(peak^2 / rmse^2) with peak 1.0 on linear values (HDR values above 1 are not
    // special-cased); +inf if rmse == 0.
    double psnr_db = 0;

    // Perceptual: both images go through tone_map_to_srgb8(., exposure), then srgb8_to_lab,
    // then ciede2000 per pixel.
    double ciede2000_mean = 0;
    double ciede2000_p99 = 0; // 99th percentile, nearest-rank: sorted[ceil(0.99 n) - 1]

    bool ok() const noexcept { return error.empty(); }
};

// Compares two images of the same size. Errors (in .error): different sizes, empty images,
// or an rgba vector whose length does not match width * height * 4.
ImageErrorStats compare_images(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                               float exposure = 1.0f);

// True if the image cannot be a meaningful render: empty, not well_formed(), or every pixel has
// the same RGB (this includes all black; NaN counts as equal to NaN). Alpha is ignored.
bool is_degenerate(const ImageRGBA32F& image);

} // namespace watergen
