// A half variant rendered at 16 bits on the GPU (strict half, see EmitOptions) and held against
// what it approximates and what models it: the same variant at full precision on the GPU, and
// the CPU evaluator's half mode over the same scene.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "watergen/eval/draw/variant_render.h"
#include "watergen/pipeline/variant/variant_build.h"
#include "watergen/water/presets.h"

namespace watergen {

// Agreement of two images of binary16 values over R, G and B; max_index is a pixel index.
HalfAgreement half_agreement(const ImageRGBA32F& test, const ImageRGBA32F& reference);

struct HalfRender {
    std::string key;
    VariantRender strict;  // both language paths, 16-bit; no CPU float pass
    ImageRGBA32F cpu_half; // CPU half evaluation of the same graph
    VariantRender full;    // the variant at precision=full (GLSL path is the reference)
    std::array<ImageErrorStats, 2> vs_cpu_half; // GLSL, HLSL path against cpu_half
    std::array<HalfAgreement, 2> ulps_vs_cpu_half;
    std::array<ImageErrorStats, 2> vs_full; // GLSL, HLSL path against full.gpu_image[0]
    ImageErrorStats cpu_half_vs_full;       // what the CPU emulation alone predicted
    Diagnostics diagnostics;                // of a build that failed
    std::string error;
    bool ok() const { return error.empty(); }
};

// What:   builds `variant` (precision must be half) with strict_half and again at precision=full,
//         renders both on `runner` over `scene`, evaluates the half graph on the CPU in half
//         mode, and compares (the images' NaN/Inf counts are in the stats).
// Cost:   three variant builds' worth of toolchain runs, four pipelines (JIT), one CPU half
//         evaluation (about 35 us per pixel).
HalfRender render_strict_half(VulkanRunner& runner, const Variant& variant, const Preset* preset,
                              const SyntheticScene& scene, const RenderSettings& settings);

// The two builds render_strict_half draws: the variant with strict_half and at precision=full.
// Built once, they draw over any number of scenes (the stability bench's points).
struct StrictHalfBuilds {
    std::string key;
    VariantBuild strict, full;
    Diagnostics diagnostics; // of a build that failed
    std::string error;
    bool ok() const { return error.empty(); }
};
StrictHalfBuilds build_strict_half(const Variant& variant, const Preset* preset);
HalfRender render_strict_half(VulkanRunner& runner, const StrictHalfBuilds& builds,
                              const SyntheticScene& scene, const RenderSettings& settings);

} // namespace watergen
