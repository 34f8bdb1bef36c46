// Error metrics between a rendered image (`test`) and the CPU reference evaluation.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "watergen/eval/image/image_io.h"

namespace watergen {

// CIELAB, D65 white (L in [0, 100]).
struct Lab {
    double L = 0, a = 0, b = 0;
};

// CIEDE2000 colour difference with kL = kC = kH = 1, as specified in G. Sharma, W. Wu,
// E. N. Dalal, "The CIEDE2000 color-difference formula: implementation notes, supplementary
// test data, and mathematical observations", Color Res. Appl. 30(1):21-30, 2005.
double ciede2000(Lab x, Lab y);

// CIE XYZ, scaled so that the sRGB white (1, 1, 1) has Y = 1.
struct XYZ {
    double X = 0, Y = 0, Z = 0;
};

// Linear sRGB -> XYZ with the IEC 61966-2-1 matrix.
XYZ linear_srgb_to_xyz(double r, double g, double b);
// The D65 white of that matrix: linear_srgb_to_xyz(1, 1, 1), its row sums.
XYZ srgb_white_xyz();

// Linear sRGB -> CIELAB: linear_srgb_to_xyz, then CIE 15 Lab relative to srgb_white_xyz(), so
// every grey maps to a = b = 0.
Lab linear_srgb_to_lab(double r, double g, double b);

// 8-bit sRGB -> CIELAB: exact sRGB decoding (srgb_to_linear), then linear_srgb_to_lab.
Lab srgb8_to_lab(uint8_t r, uint8_t g, uint8_t b);

// The nearest-rank percentile: sorted[ceil(percent * n / 100) - 1] for percent in [1, 100];
// reorders `values` (nth_element). NaN if `values` is empty.
double nearest_rank_percentile(std::span<double> values, unsigned percent);

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

// Per-pixel CIEDE2000 between the two images after tone_map_to_srgb8(., exposure) and
// srgb8_to_lab, row-major; NaN where either image has a non-finite R, G or B. Empty if the
// images differ in size or are not well_formed().
std::vector<double> ciede2000_map(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                                  float exposure = 1.0f);

// Compares two images of the same size. Errors (in .error): different sizes, empty images,
// or an rgba vector whose length does not match width * height * 4.
ImageErrorStats compare_images(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                               float exposure = 1.0f);

// True if the image cannot be a meaningful render: empty, not well_formed(), or every pixel has
// the same RGB (this includes all black; NaN counts as equal to NaN). Alpha is ignored.
bool is_degenerate(const ImageRGBA32F& image);

} // namespace watergen
