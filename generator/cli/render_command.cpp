#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/water/presets.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/render/variant_render.h"

namespace watergen::cli {

namespace {

nlohmann::ordered_json stats_json(const ImageErrorStats& s) {
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(std::to_string(v)); };
    return {{"max_abs", number(s.max_abs)},
            {"max_abs_at", {s.max_abs_location.x, s.max_abs_location.y}},
            {"rmse", number(s.rmse)},
            {"psnr_db", number(s.psnr_db)},
            {"ciede2000_mean", number(s.ciede2000_mean)},
            {"ciede2000_p99", number(s.ciede2000_p99)},
            {"nan_inf_pixels", s.nan_inf_pixels}};
}

nlohmann::ordered_json timing_json(const RenderResult& r) {
    return {{"pipeline_ms", r.pipeline_ms}, {"first_draw_ms", r.first_draw_ms},
            {"steady_draw_ms", r.steady_draw_ms}, {"draw_ms", r.draw_ms}};
}

} // namespace

Runner add_render_command(CLI::App& app, const Common& common) {
    struct Options {
        Variant variant = default_variant();
        std::string preset;
        uint32_t width = 256, height = 256, draws = 10;
        float exposure = 1.0f;
        std::string out = "out/render";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    add_variant_options(app, o->variant, o->preset);
    app.add_option("--width", o->width, "image width in pixels (default 256)")->check(CLI::Range(8, 4096));
    app.add_option("--height", o->height, "image height in pixels (default 256)")->check(CLI::Range(8, 4096));
    app.add_option("--draws", o->draws, "timed draws after the first (JIT) draw; the median is reported (default 10)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--exposure", o->exposure, "exposure applied before the sRGB PNG encoding (default 1)");
    app.add_option("--out", o->out, "output directory; files go to <out>/<variant>/ (default out/render)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        const Preset* preset = nullptr;
        if (!resolve_variant(o->variant, o->preset, &preset)) return kUsage;
        const VariantBuild build = build_variant(o->variant, preset);
        print_diagnostics(build.diagnostics, common);
        if (!build.ok()) return kFailed;
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        SyntheticScene scene = make_synthetic_scene(o->width, o->height);
        if (preset)
            for (const auto& [name, values] : preset->values) scene.uniforms[name] = values; // lighting follows the preset
        const VariantRender r = render_variant(*runner, build, scene, {o->width, o->height, o->draws, true});
        if (!r.ok()) {
            std::fprintf(stderr, "watergen: error: %s: %s\n", r.key.c_str(), r.error.c_str());
            return kFailed;
        }
        const std::filesystem::path dir = std::filesystem::path(o->out) / o->variant.file_stem();
        std::string error;
        const auto staging = make_staging_directory(dir, &error);
        bool ok = !staging.empty();
        const char* names[2] = {"glsl", "hlsl"};
        for (int i = 0; i < 2 && ok; ++i) {
            const auto rgba8 = tone_map_to_srgb8(r.gpu_image[i], o->exposure);
            ok = write_png(staging / (std::string(names[i]) + ".png"), o->width, o->height, rgba8, &error) &&
                 write_pfm(staging / (std::string(names[i]) + ".pfm"), r.gpu_image[i], &error);
        }
        ok = ok && write_pfm(staging / "cpu_float.pfm", r.cpu_float, &error);
        const DeviceInfo& dev = runner->device_info();
        nlohmann::ordered_json j;
        j["variant"] = r.key;
        j["preset"] = o->preset;
        j["image"] = {{"width", o->width}, {"height", o->height}, {"format", "RGBA32F"}};
        j["device"] = {{"name", dev.name}, {"driver", dev.driver_name}, {"driver_info", dev.driver_info},
                       {"api_version", format_api_version(dev.api_version)}};
        j["mesa_shader_cache"] = cache;
        j["spirv"] = "spirv-opt -O output of each language path";
        j["gpu"] = {{"glsl", timing_json(r.gpu[0])}, {"hlsl", timing_json(r.gpu[1])}};
        j["cpu_float_ms"] = r.cpu_float_ms;
        j["errors"] = {{"glsl_vs_hlsl", stats_json(r.glsl_vs_hlsl)},
                       {"glsl_vs_cpu_float", stats_json(r.glsl_vs_cpu_float)},
                       {"hlsl_vs_cpu_float", stats_json(r.hlsl_vs_cpu_float)},
                       {"glsl_vs_cpu_double", stats_json(r.glsl_vs_cpu_double)}};
        if (ok) {
            if (auto e = write_file_atomically(staging / "render.json", j.dump(2) + "\n")) {
                error = *e;
                ok = false;
            }
        }
        if (ok) {
            if (auto e = commit_directory(staging, dir)) {
                error = *e;
                ok = false;
            }
        } else if (!staging.empty()) {
            std::filesystem::remove_all(staging);
        }
        if (!ok) {
            std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
            return kFailed;
        }
        std::printf("%s on %s (%s), %ux%u, Mesa shader cache %s\n", r.key.c_str(), dev.name.c_str(), dev.driver_info.c_str(),
                    o->width, o->height, cache.c_str());
        std::printf("  %-5s pipeline %7.2f ms   first draw %8.2f ms   steady draw %7.3f ms (median of %u)\n", "glsl",
                    r.gpu[0].pipeline_ms, r.gpu[0].first_draw_ms, r.gpu[0].steady_draw_ms, o->draws);
        std::printf("  %-5s pipeline %7.2f ms   first draw %8.2f ms   steady draw %7.3f ms (median of %u)\n", "hlsl",
                    r.gpu[1].pipeline_ms, r.gpu[1].first_draw_ms, r.gpu[1].steady_draw_ms, o->draws);
        std::printf("  max abs: glsl-hlsl %.3g, gpu-cpu(float) %.3g, gpu-cpu(double) %.3g; NaN/Inf pixels %llu\n",
                    r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs, r.glsl_vs_cpu_double.max_abs,
                    static_cast<unsigned long long>(r.glsl_vs_cpu_float.nan_inf_pixels));
        std::printf("  wrote %s/{glsl,hlsl}.png, .pfm, cpu_float.pfm, render.json\n", dir.string().c_str());
        return kOk;
    };
}

} // namespace watergen::cli
