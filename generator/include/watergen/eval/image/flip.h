// LDR-FLIP: the perceived difference between two tone-mapped images when a viewer flips between
// them, per pixel in [0, 1]. P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson, K. Astrom,
// M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph.
// Interact. Tech. 3(2), 2020 (section numbers below are the paper's).
//
// Colour pipeline (sec. 4.1): sRGB -> linear -> XYZ -> YCxCz (linearised CIELAB), each channel
// filtered with the paper's contrast sensitivity functions as spatial kernels for the viewing
// distance (pixels per degree), back to linear RGB clamped to [0, 1], CIELAB with the Hunt
// adjustment (a, b scaled by 0.01 L), HyAB distance |dL| + ||(da, db)||, raised to qc = 0.7 and
// redistributed to [0, 1] around pc = 0.4 of cmax (the Hunt-adjusted HyAB^qc between green and
// blue): [0, pc cmax) -> [0, pt = 0.95), [pc cmax, cmax] -> [pt, 1].
// Feature pipeline (sec. 4.2): on the normalised achromatic channel Y / Yn, edges and points from
// the first and second derivatives of a Gaussian with standard deviation 0.5 * 0.082 degrees
// (kernel weights normalised so the positive ones sum to 1 and the negative ones to -1); the
// feature difference is sqrt(max(|edge_ref - edge_test|, |point_ref - point_test|) / sqrt 2).
// Result: colour^(1 - feature).
//
// Choices of this implementation (the paper leaves them open): the XYZ matrix and white are
// runtime's (linear_srgb_to_xyz, srgb_white_xyz: IEC 61966-2-1, white = its row sums); borders
// replicate the edge pixel; every kernel is applied as separable passes in float.
// Symmetry: the colour term is symmetric in the two images and the feature term is too (both are
// absolute differences of per-image quantities), so flip(a, b) == flip(b, a) up to rounding; the
// paper's asymmetry (reference vs test) matters only for HDR-FLIP, not implemented here.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "watergen/eval/image/image_io.h"

namespace watergen {

// The paper's default: a 0.7 m wide 3840-pixel monitor seen from 0.7 m (67.02 ppd).
constexpr double kFlipDefaultPixelsPerDegree = 67.0;

struct FlipMap {
    std::string error; // non-empty: not computed (sizes differ, empty or malformed input)
    uint32_t width = 0, height = 0;
    std::vector<float> values; // per pixel in [0, 1], row-major, row 0 = top
    // Over all pixels; percentiles are nearest-rank (nearest_rank_percentile).
    double mean = 0, p50 = 0, p95 = 0, p99 = 0, max = 0;

    bool ok() const noexcept { return error.empty(); }
};

// FLIP between two 8-bit sRGB images of the same size (alpha ignored).
FlipMap flip_srgb8(const ImageRGBA8& reference, const ImageRGBA8& test,
                   double pixels_per_degree = kFlipDefaultPixelsPerDegree);

// FLIP between two linear float images, both tone-mapped first with tone_map_to_srgb8(., exposure)
// (NaN/Inf pixels become its magenta marker, so they show as large differences).
FlipMap flip_linear(const ImageRGBA32F& reference, const ImageRGBA32F& test, float exposure = 1.0f,
                    double pixels_per_degree = kFlipDefaultPixelsPerDegree);

// The colour term's redistribution constant: (Hunt-adjusted HyAB(green, blue))^0.7.
double flip_cmax();

} // namespace watergen
