#include "watergen/render/render_report.h"

#include <cmath>

#include "watergen/pipeline/output_writer.h"

namespace watergen {

namespace {

nlohmann::ordered_json number(double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(std::to_string(v));
}

nlohmann::ordered_json stats_json(const ImageErrorStats& s) {
    return {{"max_abs", number(s.max_abs)},
            {"max_abs_at", {s.max_abs_location.x, s.max_abs_location.y}},
            {"rmse", number(s.rmse)},
            {"psnr_db", number(s.psnr_db)},
            {"ciede2000_mean", number(s.ciede2000_mean)},
            {"ciede2000_p99", number(s.ciede2000_p99)},
            {"nan_inf_pixels", s.nan_inf_pixels},
            {"reference_nan_inf_pixels", s.reference_nan_inf_pixels},
            {"nan_inf_where_reference_finite", s.nan_inf_where_reference_finite}};
}

nlohmann::ordered_json timing_json(const RenderResult& r) {
    return {{"pipeline_ms", r.pipeline_ms},
            {"first_draw_ms", r.first_draw_ms},
            {"steady_draw_ms", r.steady_draw_ms},
            {"draw_ms", r.draw_ms}};
}

std::optional<std::string> write_images(const std::filesystem::path& staging,
                                        const VariantRender& r, const RenderReportInfo& info) {
    std::string error;
    const char* names[2] = {"glsl", "hlsl"};
    for (int i = 0; i < 2; ++i) {
        const auto rgba8 = tone_map_to_srgb8(r.gpu_image[i], static_cast<float>(info.exposure));
        if (!write_png(staging / (std::string(names[i]) + ".png"), info.width, info.height, rgba8,
                       &error) ||
            !write_pfm(staging / (std::string(names[i]) + ".pfm"), r.gpu_image[i], &error))
            return error;
    }
    if (!write_pfm(staging / "cpu_float.pfm", r.cpu_float, &error)) return error;
    return std::nullopt;
}

} // namespace

uint64_t gpu_only_non_finite_pixels(const VariantRender& r) {
    return std::max(r.glsl_vs_cpu_float.nan_inf_where_reference_finite,
                    r.hlsl_vs_cpu_float.nan_inf_where_reference_finite);
}

nlohmann::ordered_json render_report_json(const VariantRender& r, const RenderReportInfo& info) {
    const DeviceInfo& dev = info.device;
    nlohmann::ordered_json j;
    j["variant"] = r.key;
    j["preset"] = info.preset;
    j["image"] = {{"width", info.width}, {"height", info.height}, {"format", "RGBA32F"}};
    j["device"] = {{"name", dev.name},
                   {"driver", dev.driver_name},
                   {"driver_info", dev.driver_info},
                   {"api_version", format_api_version(dev.api_version)}};
    j["mesa_shader_cache"] = info.shader_cache;
    j["spirv"] = "spirv-opt -O output of each language path";
    j["gpu"] = {{"glsl", timing_json(r.gpu[0])}, {"hlsl", timing_json(r.gpu[1])}};
    j["cpu_float_ms"] = r.cpu_float_ms;
    j["errors"] = {{"glsl_vs_hlsl", stats_json(r.glsl_vs_hlsl)},
                   {"glsl_vs_cpu_float", stats_json(r.glsl_vs_cpu_float)},
                   {"hlsl_vs_cpu_float", stats_json(r.hlsl_vs_cpu_float)},
                   {"glsl_vs_cpu_double", stats_json(r.glsl_vs_cpu_double)}};
    j["gpu_only_non_finite_pixels"] = gpu_only_non_finite_pixels(r);
    return j;
}

std::optional<std::string> write_render_report(const std::filesystem::path& dir,
                                               const VariantRender& r,
                                               const RenderReportInfo& info) {
    std::string error;
    const auto staging = make_staging_directory(dir, &error);
    if (staging.empty()) return error;
    auto result = write_images(staging, r, info);
    if (!result)
        result = write_file_atomically(staging / "render.json",
                                       render_report_json(r, info).dump(2) + "\n");
    if (!result) result = commit_directory(staging, dir);
    if (result) {
        std::error_code ec;
        std::filesystem::remove_all(staging, ec);
    }
    return result;
}

} // namespace watergen
