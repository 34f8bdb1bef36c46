// `watergen render` as a library call: one variant built, drawn through both language paths
// over a view of the synthetic scene (a caustics variant over its own pass's texture,
// variant_caustics.h), evaluated on the CPU, and written with render.json (render_report.h)
// into <out>/<variant>/, or <out>/<variant>_view-<view>/ for a view other than beach, so that
// renders of one variant in several views sit side by side. --strict-half is its own run.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "watergen/eval/draw/draw_device.h"
#include "watergen/eval/draw/variant_caustics.h"
#include "watergen/eval/report/render_report.h"
#include "watergen/ir/cpu/float_error.h"

namespace watergen {

struct RenderRequest {
    Variant variant = default_variant();
    const Preset* preset = nullptr;
    std::string view = "beach";
    // Where the scene stands (SceneView::world_offset, m): the whole scene, eye included, moves
    // by it. Values given for the scene's positions (eye_position, water_level, the x0, z0 of
    // caustics_window and fourier_map_origin) are relative to it: the offset is added to them.
    std::array<double, 3> world_offset{};
    uint32_t width = 256, height = 256, draws = 10; // timed draws after the first (JIT) draw
    double exposure = 1.0;                          // of the PNG previews
    double tolerance = kAgreementTolerance;         // GPU against CPU float, beyond the bound
    LoopUnroll unroll = LoopUnroll::AsHinted;       // every loop's hint (not with strict half)
    std::filesystem::path out = "out/render";
    std::string shader_cache; // Mesa's shader cache as the device was opened (render.json)
    // Parameter values over the preset's and the view's, for the GPU and the CPU alike (render
    // --set): each must name a parameter of the variant, with its number of components. The
    // scene's depth buffer follows the depth conventions set here and the eye set here; a
    // position is given in the scene's own frame and moved by world_offset (placed_scene_value).
    std::map<std::string, std::vector<double>> values = {};
    // Where the variant binds its resources (render --bindings); null: the default profile. The
    // runner binds by reflection, so the draw follows the map (a pushed block is pushed).
    const BindingMap* bindings = nullptr;
    WaterGridDesc grid{}; // a mesh variant's grid (render --grid-*)
};

// Where a render of `variant` in `view` goes under `out`.
std::filesystem::path render_directory(const std::filesystem::path& out, const Variant& variant,
                                       const std::string& view);

struct RenderRun {
    RenderReportInfo info;
    std::filesystem::path dir;
    VariantRender render;
    std::optional<RenderCaustics> caustics; // a variant with caustics
    Diagnostics diagnostics;                // the variant's build's, then its caustics pass's
    std::string error;                      // "<variant>: <what>", or the write's failure
    RunStatus status = RunStatus::Ok;
    // Pixels NaN/Inf on the GPU where the CPU float image is finite (gpu_only_non_finite_pixels).
    uint64_t gpu_only_non_finite = 0;
    // When a pixel differs from the CPU float image by more than the tolerance: the worst one
    // (Agreement::worst of the GLSL path) traced to the operations it depends on.
    std::optional<PixelAttribution> worst;
};

// Cost: a variant build, two pipelines (JIT), the CPU evaluations; for a pass choice its build,
// two pipelines and the CPU photon reference.
RenderRun run_render(VulkanRunner& runner, const RenderRequest& request);

struct HalfRenderRun {
    RenderReportInfo info;
    std::filesystem::path dir;
    HalfRender half; // its diagnostics: of a build that failed
    std::string error;
    RunStatus status = RunStatus::Ok;
    // Pixels NaN/Inf in 16-bit arithmetic on the GPU (either path) where the CPU half image is
    // finite.
    uint64_t gpu_only_non_finite = 0;
};

// `watergen render --strict-half` of a precision=half variant (render_strict_half) on a device
// with shaderFloat16, written with its comparisons (write_half_render_report).
HalfRenderRun run_strict_half_render(VulkanRunner& runner, const RenderRequest& request);

} // namespace watergen
