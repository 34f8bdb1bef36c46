// What `watergen render` writes for one variant: the two GPU images as PNG (tone-mapped sRGB)
// and PFM (raw float), the CPU reference image, and render.json (device, times, error figures
// and NaN/Inf counts per side). Written into a staging directory and swapped in whole.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "watergen/eval/draw/half_render.h"
#include "watergen/eval/draw/variant_render.h"
#include "watergen/ir/cpu/float_error.h"

namespace watergen {

struct RenderReportInfo {
    std::string preset;
    std::string shader_cache; // "off" or the directory
    DeviceInfo device;
    uint32_t width = 0, height = 0;
    double exposure = 1.0;                // of the PNG previews only
    std::string view = "beach";           // of the synthetic scene (scene_views.h)
    std::array<double, 3> world_offset{}; // m: where the scene stood (SceneView::world_offset)
};

// Pixels non-finite on the GPU (either path) where the CPU float image is finite: a variant
// that breaks on the GPU where the reference does not.
uint64_t gpu_only_non_finite_pixels(const VariantRender& r);

nlohmann::ordered_json render_report_json(const VariantRender& r, const RenderReportInfo& info);

// render.json's "agreement": each path's Agreement with the CPU float image (the tolerance, the
// float error bound's model, the pixels over each), and when a pixel is over the tolerance,
// the worst one's values and the operations whose float rounding moves it most.
nlohmann::ordered_json agreement_json(const VariantRender& r, const PixelAttribution* worst);

// What a render adds beside its images (caustics: variant_caustics.h): keys appended to
// render.json and files by name. Empty for most variants: their files stay as they were.
struct RenderExtras {
    nlohmann::ordered_json json = nlohmann::ordered_json::object();
    std::map<std::string, std::string> files;
};

// Writes the files into `dir` (replacing a previous render of the variant); an error message
// on failure, with nothing half-written.
std::optional<std::string> write_render_report(const std::filesystem::path& dir,
                                               const VariantRender& r, const RenderReportInfo& info,
                                               const RenderExtras& extras = {});

// `watergen render --strict-half`: the strict-half GPU images (glsl, hlsl as .png and .pfm),
// cpu_half.pfm, full_precision.pfm (GPU, GLSL) and render.json with every comparison.
nlohmann::ordered_json half_render_report_json(const HalfRender& h, const RenderReportInfo& info);
std::optional<std::string> write_half_render_report(const std::filesystem::path& dir,
                                                    const HalfRender& h,
                                                    const RenderReportInfo& info);

} // namespace watergen
