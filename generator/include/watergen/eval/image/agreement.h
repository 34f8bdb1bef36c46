// Agreement of a GPU image with the CPU's float image, pixel by pixel, against a tolerance plus
// the float error to expect at each pixel (float_error_spread, watergen/ir/cpu/float_error.h): a
// pixel over the tolerance is explained when it is within its own bound, and a failure when
// it is not.
#pragma once

#include <cstdint>
#include <vector>

#include "watergen/eval/image/image_metrics.h"

namespace watergen {

// The tolerance every render and test holds GPU and CPU float images to unless told otherwise.
constexpr double kAgreementTolerance = 5e-5;

struct Agreement {
    double tolerance = kAgreementTolerance;
    uint64_t compared = 0;       // pixels with finite RGB on both sides
    uint64_t over_tolerance = 0; // max |test - reference| over R, G, B above `tolerance`
    uint64_t over_bound = 0;     // ... above tolerance + the pixel's bound: unexplained
    double max_bound = 0;        // the largest bound of a pixel
    // The pixel furthest over its allowance (tolerance + bound), or when none is over, the
    // pixel of the largest difference; first in row-major order.
    PixelLocation worst;
    double worst_difference = 0, worst_bound = 0;
    bool holds() const { return over_bound == 0; }
};

// `bound`: width x height values, row 0 = top (empty: 0 everywhere).
Agreement check_agreement(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                          const std::vector<float>& bound, double tolerance);

} // namespace watergen
