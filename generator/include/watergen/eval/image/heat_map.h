// Error values as pictures: a perceptually ordered colour map (magma: black through purple and
// orange to pale yellow, lightness rising monotonically), a fixed scale per metric so maps of
// different variants compare at a glance, and the colour bar that reads them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "watergen/eval/image/image_io.h"

namespace watergen {

// Values map linearly from [lo, hi] onto the colour map, clamped at both ends.
struct HeatScale {
    std::string label;         // what the values are, e.g. "CIEDE2000"
    double lo = 0, hi = 1;     // the colour map's two ends
    std::vector<double> ticks; // values to label on the colour bar, within [lo, hi], ascending
};

// CIEDE2000 on [0, 10]; ticks at 0, 2.3 (just noticeable), 5 and 10. Larger values clip.
HeatScale ciede2000_scale();
// FLIP on its own range [0, 1]; ticks every 0.25.
HeatScale flip_scale();

// Magma at t in [0, 1] (clamped), interpolated linearly in sRGB between 9 samples of
// matplotlib's table (t = 0, 1/8, ..., 1).
std::array<uint8_t, 3> magma(double t);

// The colour of non-finite values: pure green, a hue magma never reaches.
constexpr std::array<uint8_t, 3> kHeatNonFiniteColor{0, 255, 0};

// `values` (row-major, width * height) coloured with magma on `scale`; non-finite values get
// kHeatNonFiniteColor. Empty image if values.size() != width * height.
ImageRGBA8 heat_map(std::span<const float> values, uint32_t width, uint32_t height,
                    const HeatScale& scale);

// A horizontal colour bar: column x shows the colour of lo + (hi - lo) * x / (width - 1), so the
// first column is the colour of lo and the last the colour of hi.
ImageRGBA8 color_bar(const HeatScale& scale, uint32_t width, uint32_t height);

// Where `value` sits along the bar, in [0, 1] (for placing tick labels).
double scale_position(const HeatScale& scale, double value);

} // namespace watergen
