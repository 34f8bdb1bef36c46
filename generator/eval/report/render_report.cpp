#include "watergen/eval/report/render_report.h"

#include <cmath>

#include "watergen/pipeline/output/output_writer.h"

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

// The GPU images as <name>.png and .pfm, then each reference image as <name>.pfm.
std::optional<std::string>
write_images(const std::filesystem::path& staging, const VariantRender& r,
             const RenderReportInfo& info,
             const std::vector<std::pair<std::string, const ImageRGBA32F*>>& references) {
    std::string error;
    const char* names[2] = {"glsl", "hlsl"};
    for (int i = 0; i < 2; ++i) {
        const auto rgba8 = tone_map_to_srgb8(r.gpu_image[i], static_cast<float>(info.exposure));
        if (!write_png(staging / (std::string(names[i]) + ".png"), info.width, info.height, rgba8,
                       &error) ||
            !write_pfm(staging / (std::string(names[i]) + ".pfm"), r.gpu_image[i], &error))
            return error;
    }
    for (const auto& [name, image] : references)
        if (!write_pfm(staging / (name + ".pfm"), *image, &error)) return error;
    return std::nullopt;
}

nlohmann::ordered_json device_json(const DeviceInfo& dev) {
    return {{"name", dev.name},
            {"driver", dev.driver_name},
            {"driver_info", dev.driver_info},
            {"api_version", format_api_version(dev.api_version)}};
}

nlohmann::ordered_json ulps_json(const HalfAgreement& a, uint32_t width) {
    return {{"channels", a.values},
            {"equal", a.equal},
            {"within_1_ulp", a.within_1},
            {"max_ulps", a.max_ulps},
            {"max_at", {a.max_index % width, a.max_index / width}}};
}

// The per-pixel float error bound as a grey image (R = G = B = the bound): float_bound.pfm.
ImageRGBA32F bound_image(const VariantRender& r, uint32_t width, uint32_t height) {
    ImageRGBA32F img{width, height, std::vector<float>(size_t(width) * height * 4, 1.0f)};
    for (size_t p = 0; p < r.float_bound.size() && p < size_t(width) * height; ++p)
        for (size_t c = 0; c < 3; ++c)
            img.rgba[p * 4 + c] = r.float_bound[p];
    return img;
}

// Stages the images and render.json, then swaps the directory in whole.
std::optional<std::string>
write_report(const std::filesystem::path& dir, const VariantRender& r, const RenderReportInfo& info,
             const std::vector<std::pair<std::string, const ImageRGBA32F*>>& references,
             const nlohmann::ordered_json& json,
             const std::map<std::string, std::string>& extra_files = {}) {
    std::string error;
    const auto staging = make_staging_directory(dir, &error);
    if (staging.empty()) return error;
    auto result = write_images(staging, r, info, references);
    for (const auto& [name, contents] : extra_files)
        if (!result) result = write_file_atomically(staging / name, contents);
    if (!result) result = write_file_atomically(staging / "render.json", json.dump(2) + "\n");
    if (!result) result = commit_directory(staging, dir);
    if (result) {
        std::error_code ec;
        std::filesystem::remove_all(staging, ec);
    }
    return result;
}

} // namespace

nlohmann::ordered_json agreement_json(const VariantRender& r, const PixelAttribution* worst) {
    auto side = [](const Agreement& a) {
        return nlohmann::ordered_json{{"compared_pixels", a.compared},
                                      {"over_tolerance", a.over_tolerance},
                                      {"over_tolerance_and_bound", a.over_bound},
                                      {"max_bound", number(a.max_bound)},
                                      {"worst_at", {a.worst.x, a.worst.y}},
                                      {"worst_difference", number(a.worst_difference)},
                                      {"worst_bound", number(a.worst_bound)}};
    };
    nlohmann::ordered_json j;
    j["tolerance"] = r.agreement[0].tolerance;
    j["bound"] = "per pixel (float_bound.pfm): twice the largest change of the double image over " +
                 std::to_string(kFloatBoundRuns) +
                 " runs moving every product, quotient, transcendental, built-in and filtered "
                 "sample by up to one binary32 ulp (2^-23 relative)";
    j["glsl"] = side(r.agreement[0]);
    j["hlsl"] = side(r.agreement[1]);
    if (worst && worst->ok()) {
        const PixelLocation at = r.agreement[0].worst;
        const size_t p = (size_t(at.y) * r.gpu_image[0].width + at.x) * 4;
        nlohmann::ordered_json nodes = nlohmann::ordered_json::array();
        for (const SiteEffect& e : worst->effects)
            nodes.push_back(
                {{"origin", e.what.origin},
                 {"operation", std::string(op_name(e.what.op)) + "(" + e.what.operands + ")"},
                 {"name", e.what.name},
                 {"change", number(e.change)}});
        std::vector<double> gpu;
        for (size_t c = 0; c < worst->double_value.size() && c < 4; ++c)
            gpu.push_back(r.gpu_image[0].rgba[p + c]);
        j["worst_pixel"] = {{"at", {at.x, at.y}},
                            {"cpu_double", worst->double_value},
                            {"cpu_float", worst->float_value},
                            {"glsl", gpu},
                            {"nodes_by_float_rounding", nodes}};
    }
    return j;
}

uint64_t gpu_only_non_finite_pixels(const VariantRender& r) {
    return std::max(r.glsl_vs_cpu_float.nan_inf_where_reference_finite,
                    r.hlsl_vs_cpu_float.nan_inf_where_reference_finite);
}

nlohmann::ordered_json render_report_json(const VariantRender& r, const RenderReportInfo& info) {
    const DeviceInfo& dev = info.device;
    nlohmann::ordered_json j;
    j["variant"] = r.key;
    j["preset"] = info.preset;
    j["view"] = info.view;
    j["world_offset"] = info.world_offset;
    j["image"] = {{"width", info.width}, {"height", info.height}, {"format", "RGBA32F"}};
    j["device"] = device_json(dev);
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
                                               const VariantRender& r, const RenderReportInfo& info,
                                               const RenderExtras& extras) {
    nlohmann::ordered_json json = render_report_json(r, info);
    for (const auto& [key, value] : extras.json.items())
        json[key] = value;
    std::vector<std::pair<std::string, const ImageRGBA32F*>> references = {
        {"cpu_float", &r.cpu_float}};
    const ImageRGBA32F bound = bound_image(r, info.width, info.height);
    if (!r.float_bound.empty()) references.push_back({"float_bound", &bound});
    return write_report(dir, r, info, references, json, extras.files);
}

nlohmann::ordered_json half_render_report_json(const HalfRender& h, const RenderReportInfo& info) {
    const VariantRender& r = h.strict;
    nlohmann::ordered_json j;
    j["variant"] = h.key;
    j["preset"] = info.preset;
    j["view"] = info.view;
    j["world_offset"] = info.world_offset;
    j["strict_half"] = "relaxed math in explicit 16-bit types (GLSL float16_t, HLSL half); "
                       "reference: the same variant at precision=full, GLSL path";
    j["image"] = {{"width", info.width}, {"height", info.height}, {"format", "RGBA32F"}};
    j["device"] = device_json(info.device);
    j["mesa_shader_cache"] = info.shader_cache;
    j["gpu"] = {{"glsl", timing_json(r.gpu[0])},
                {"hlsl", timing_json(r.gpu[1])},
                {"full_precision_glsl", timing_json(h.full.gpu[0])}};
    j["errors"] = {{"glsl_vs_hlsl", stats_json(r.glsl_vs_hlsl)},
                   {"glsl_vs_cpu_half", stats_json(h.vs_cpu_half[0])},
                   {"hlsl_vs_cpu_half", stats_json(h.vs_cpu_half[1])},
                   {"glsl_vs_full", stats_json(h.vs_full[0])},
                   {"hlsl_vs_full", stats_json(h.vs_full[1])},
                   {"cpu_half_vs_full", stats_json(h.cpu_half_vs_full)}};
    j["ulps_vs_cpu_half"] = {{"glsl", ulps_json(h.ulps_vs_cpu_half[0], info.width)},
                             {"hlsl", ulps_json(h.ulps_vs_cpu_half[1], info.width)}};
    return j;
}

std::optional<std::string> write_half_render_report(const std::filesystem::path& dir,
                                                    const HalfRender& h,
                                                    const RenderReportInfo& info) {
    return write_report(dir, h.strict, info,
                        {{"cpu_half", &h.cpu_half}, {"full_precision", &h.full.gpu_image[0]}},
                        half_render_report_json(h, info));
}

} // namespace watergen
