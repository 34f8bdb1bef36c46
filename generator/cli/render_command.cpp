#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "watergen/render/render_report.h"
#include "watergen/water/presets.h"

namespace watergen::cli {

namespace {

void print_render(const VariantRender& r, const RenderReportInfo& info, uint32_t draws,
                  const std::filesystem::path& dir) {
    const DeviceInfo& dev = info.device;
    std::printf("%s on %s (%s), %ux%u, Mesa shader cache %s\n", r.key.c_str(), dev.name.c_str(),
                dev.driver_info.c_str(), info.width, info.height, info.shader_cache.c_str());
    std::printf("  %-5s pipeline %7.2f ms   first draw %8.2f ms   steady draw %7.3f ms (median "
                "of %u)\n",
                "glsl", r.gpu[0].pipeline_ms, r.gpu[0].first_draw_ms, r.gpu[0].steady_draw_ms,
                draws);
    std::printf("  %-5s pipeline %7.2f ms   first draw %8.2f ms   steady draw %7.3f ms (median "
                "of %u)\n",
                "hlsl", r.gpu[1].pipeline_ms, r.gpu[1].first_draw_ms, r.gpu[1].steady_draw_ms,
                draws);
    std::printf("  max abs: glsl-hlsl %.3g, gpu-cpu(float) %.3g, gpu-cpu(double) %.3g (over "
                "pixels finite on "
                "both sides)\n",
                r.glsl_vs_hlsl.max_abs, r.glsl_vs_cpu_float.max_abs, r.glsl_vs_cpu_double.max_abs);
    std::printf("  NaN/Inf pixels: glsl %llu, hlsl %llu, cpu float %llu\n",
                static_cast<unsigned long long>(r.glsl_vs_cpu_float.nan_inf_pixels),
                static_cast<unsigned long long>(r.hlsl_vs_cpu_float.nan_inf_pixels),
                static_cast<unsigned long long>(r.glsl_vs_cpu_float.reference_nan_inf_pixels));
    std::printf("  wrote %s/{glsl,hlsl}.png, .pfm, cpu_float.pfm, render.json\n",
                dir.string().c_str());
}

} // namespace

Runner add_render_command(CLI::App& app, const Common& common) {
    struct Options {
        Variant variant = default_variant();
        std::string preset;
        uint32_t width = 256, height = 256, draws = 10;
        double exposure = 1.0;
        std::string out = "out/render";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    add_variant_options(app, o->variant, o->preset);
    app.add_option("--width", o->width, "image width in pixels (default 256)")
        ->check(CLI::Range(8, 4096));
    app.add_option("--height", o->height, "image height in pixels (default 256)")
        ->check(CLI::Range(8, 4096));
    app.add_option("--draws", o->draws,
                   "timed draws after the first (JIT) draw; the median is reported (default 10)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--exposure", o->exposure,
                   "exposure applied before the sRGB PNG encoding (default 1)")
        ->check(finite_range(1e-6, 1e6));
    app.add_option("--out", o->out,
                   "output directory; files go to <out>/<variant>/ (default out/render)");
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
            for (const auto& [name, values] : preset->values)
                scene.uniforms[name] = values; // lighting follows the preset
        const VariantRender r =
            render_variant(*runner, build, scene, {o->width, o->height, o->draws, true});
        if (!r.ok()) {
            std::fprintf(stderr, "watergen: error: %s: %s\n", r.key.c_str(), r.error.c_str());
            return kFailed;
        }
        const std::filesystem::path dir = std::filesystem::path(o->out) / o->variant.file_stem();
        const DeviceInfo& dev = runner->device_info();
        const RenderReportInfo info{o->preset, cache, dev, o->width, o->height, o->exposure};
        if (auto e = write_render_report(dir, r, info)) {
            std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
            return kFailed;
        }
        print_render(r, info, o->draws, dir);
        if (const uint64_t broken = gpu_only_non_finite_pixels(r); broken > 0) {
            std::fprintf(stderr,
                         "watergen: error: %s: %llu pixel%s NaN/Inf on the GPU where the CPU float "
                         "image is finite\n",
                         r.key.c_str(), static_cast<unsigned long long>(broken),
                         broken == 1 ? " is" : "s are");
            return kFailed;
        }
        return kOk;
    };
}

} // namespace watergen::cli
