// What every render test asserts of a variant drawn through both language paths on lavapipe
// against the CPU evaluator in float (render_variant, variant_render.h).
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "watergen/eval/draw/variant_render.h"

namespace watergen::test {

// No validation message; GLSL and HLSL within 1e-6 (both run the same IR through spirv-opt:
// measured bit-identical); each within `cpu_bound` of the CPU float image; no NaN or Inf on
// either side; an image that is not flat.
inline void check_paths_agree(const VariantRender& r, double cpu_bound) {
    for (const auto& m : r.validation_messages)
        UNSCOPED_INFO(m);
    CHECK(r.validation_messages.empty());
    CHECK(r.glsl_vs_hlsl.max_abs <= 1e-6);
    CHECK(r.glsl_vs_cpu_float.max_abs <= cpu_bound);
    CHECK(r.hlsl_vs_cpu_float.max_abs <= cpu_bound);
    CHECK(r.glsl_vs_cpu_float.nan_inf_pixels == 0);
    CHECK(r.hlsl_vs_cpu_float.nan_inf_pixels == 0);
    CHECK(r.glsl_vs_cpu_float.reference_nan_inf_pixels == 0);
    CHECK_FALSE(is_degenerate(r.gpu_image[0]));
}

// The largest difference of two images' values, any channel.
inline double max_difference(const ImageRGBA32F& a, const ImageRGBA32F& b) {
    double worst = 0;
    for (size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i)
        worst = std::max(worst, double(std::fabs(a.rgba[i] - b.rgba[i])));
    return worst;
}

} // namespace watergen::test
