// A built caustics pass drawn on the Vulkan runner: its grid over the window into the caustics
// texture (additive blending), both language paths, and measured against the CPU reference of
// the same parameter values texel by texel. The pass is the one `watergen build` ships
// (build_caustics_pass_files), built uncached so that its languages carry the SPIR-V.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "watergen/caustics/caustics_pass.h"
#include "watergen/caustics/caustics_reference.h"
#include "watergen/eval/image/image_io.h"
#include "watergen/eval/image/image_metrics.h"
#include "watergen/pipeline/manifest/caustics_pass_build.h"
#include "watergen/runner/vulkan_runner.h"

namespace watergen {

// Parameter values by name: the pass's defaults (its vertex stage's parameters) overlaid with
// `values`.
std::map<std::string, std::vector<double>>
caustics_values(const CausticsPassBuild& build,
                const std::map<std::string, std::vector<double>>& values);

// Grid cells (photons) per texel side each method is drawn with unless told otherwise: area
// ratio 2 (its triangles interpolate within a cell), photon splatting 8 (64 photons per texel;
// the binning noise is RMSE 0.096 at 16 per texel, 0.033-0.038 at 64).
uint32_t default_cells_per_texel(CausticsMethod method);

struct CausticsRenderSettings {
    uint32_t texels = 256;        // texture side
    uint32_t cells_per_texel = 2; // grid cells per texel side
    double margin = 0;            // the grid extends this far beyond the window on every side, m
    uint32_t timed_draws = 0;
};

struct CausticsRender {
    std::array<RenderResult, 2> gpu;              // GLSL path, HLSL path
    std::array<std::vector<double>, 2> intensity; // the r channel, row-major (row = z)
    ImageErrorStats glsl_vs_hlsl;
    std::string error;
    bool ok() const { return error.empty(); }
};

// Draws both paths with `values` (caustics_values) over a grid covering the window grown by
// settings.margin, cells_per_texel grid cells per texel side (photon_splat: one photon per grid
// point, caustics_photon_share set to match).
CausticsRender render_caustics(VulkanRunner& runner, const CausticsPassBuild& build,
                               const std::map<std::string, std::vector<double>>& values,
                               const CausticsRenderSettings& settings);

// The runner job that draws one language path (0 GLSL, 1 HLSL) of `build` as render_caustics
// does (additive blending); timing draws these interleaved. Empty SPIR-V and the reason in
// *error for a window that is not (x0, z0, size > 0).
RenderJob caustics_job(const CausticsPassBuild& build, size_t language,
                       const std::map<std::string, std::vector<double>>& values,
                       const CausticsRenderSettings& settings, std::string* error);

// A pass's texture against the reference's, texel by texel: the largest difference, the RMSE,
// and the mean of pass minus reference (the light the pass gains or loses). Zeros when the sizes
// differ or are 0.
struct CausticsError {
    double max_abs = 0, rmse = 0, mean_difference = 0;
};
CausticsError caustics_error(const std::vector<double>& pass, const std::vector<double>& reference);

// A texture as a grey sRGB image, intensity 4 at white (the peaks of a sunny bottom are 2-5):
// the tone map every caustics PNG uses (kCausticsToneMap says it in words).
ImageRGBA8 caustics_image(const std::vector<double>& intensity, uint32_t texels);
inline constexpr const char* kCausticsToneMap =
    "grey, intensity / 4 at white (1 = flat water at 25%), sRGB-encoded";

} // namespace watergen
