// Where a float evaluation's error comes from, and how large float rounding can make it: the
// double evaluation with the float model's rounding applied at chosen operations
// (FloatPerturbation, cpu_evaluator.h). A GPU computes in binary32 with its own roundings
// (fused multiply-adds, its own exp2 and sin), so the CPU float image is one float result among
// many; the double image is what they all approximate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "watergen/ir/cpu/cpu_evaluator.h"

namespace watergen {

// What rounding one operation to binary32 does to a pixel of the double image: the largest
// change over the output's components.
struct SiteEffect {
    size_t site = 0;
    EvalSite what;
    double change = 0;
};

struct PixelAttribution {
    std::vector<SiteEffect> effects;               // the largest first, at most `keep`
    std::vector<double> double_value, float_value; // the pixel's components
    std::string error;
    bool ok() const { return error.empty(); }
};

// Pixel (x, y) of the width x height image of `output` (row 0 = top, as evaluate_image): its
// double and float values and the operations whose binary32 rounding alone moves the double
// value most. One evaluation of the pixel's quad per operation.
PixelAttribution attribute_float_error(const Graph& g, const std::string& output,
                                       const EvalInputs& inputs, uint32_t width, uint32_t height,
                                       uint32_t x, uint32_t y, size_t keep = 5);

// The float error to expect per pixel: over `runs` double evaluations with every operation's
// results moved by a pseudo-random relative amount up to `relative` (FloatPerturbation), the
// largest change of the pixel's components from `double_image` (evaluate_image's layout and
// components). `relative` = 2^-24 models binary32 rounding to nearest; operations a GPU computes
// less exactly make it larger.
struct ErrorSpread {
    std::vector<float> per_pixel; // width x height, row 0 = top
    std::string error;
    bool ok() const { return error.empty(); }
};
ErrorSpread float_error_spread(const Graph& g, const std::string& output, const EvalInputs& inputs,
                               uint32_t width, uint32_t height, const EvalResult& double_image,
                               int runs, double relative);

} // namespace watergen
