// `watergen caustics`: the caustics passes (area ratio, photon splatting) drawn on the Vulkan
// runner for one wave model, against the CPU photon reference: the textures as PNG images, the
// pass time on the device, each method's error against the reference, and the light the clamp
// loses. Writes <out>/caustics-<waves>/ whole (a staged directory swapped in).
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/eval/draw/caustics_render.h"
#include "watergen/eval/image/image_io.h"
#include "watergen/pipeline/output_writer.h"
#include "watergen/water/presets.h"

namespace watergen::cli {

namespace {

struct Options {
    std::string waves = "gerstner", method = "both", preset;
    double depth = 3, clamp = 5;
    uint32_t size = 256, draws = 5, cells = 0;
    std::string out = "out/caustics";
    RunnerSetup runner;
};

struct MethodResult {
    CausticsMethod method;
    double steady_ms = 0, mean = 0, mean_unclamped = 0, max_abs = 0, rmse = 0, glsl_vs_hlsl = 0;
    std::vector<double> intensity;
};

// The texture as a grey PNG (caustics_image's tone map).
std::string png(const std::vector<double>& intensity, uint32_t size, std::string* error) {
    const ImageRGBA8 image = caustics_image(intensity, size);
    return encode_png(size, size, image.rgba, error);
}

// Draws one method; false after printing the failure.
bool draw_method(VulkanRunner& runner, const Options& o, const CausticsBuild& build,
                 const std::map<std::string, std::vector<double>>& given, double margin,
                 const CausticsImage& reference, MethodResult& out) {
    const CausticsMethod method = build.pass.method;
    CausticsRenderSettings settings;
    settings.texels = o.size;
    settings.margin = margin;
    settings.cells_per_texel = o.cells ? o.cells : default_cells_per_texel(method);
    settings.timed_draws = o.draws;
    auto values = caustics_values(build, given);
    const CausticsRender r = render_caustics(runner, build, values, settings);
    if (!r.ok()) {
        std::fprintf(stderr, "watergen: error: %s: %s\n", to_string(method), r.error.c_str());
        return false;
    }
    out.method = method;
    out.steady_ms = r.gpu[0].steady_draw_ms;
    out.intensity = r.intensity[0];
    out.mean = out.mean_unclamped = mean_intensity(out.intensity);
    out.glsl_vs_hlsl = r.glsl_vs_hlsl.max_abs;
    const CausticsError error = caustics_error(out.intensity, reference.intensity);
    out.max_abs = error.max_abs;
    out.rmse = error.rmse;
    if (method == CausticsMethod::AreaRatio) {
        values["caustics_clamp"] = {1e30};
        settings.timed_draws = 0;
        const CausticsRender u = render_caustics(runner, build, values, settings);
        if (!u.ok()) {
            std::fprintf(stderr, "watergen: error: %s: %s\n", to_string(method), u.error.c_str());
            return false;
        }
        out.mean_unclamped = mean_intensity(u.intensity[0]);
    }
    return true;
}

int run(const Options& o) {
    std::map<std::string, std::vector<double>> given;
    if (!o.preset.empty())
        if (const Preset* p = find_preset(o.preset)) given = p->values;
    given["caustics_depth"] = {o.depth};
    given["caustics_clamp"] = {o.clamp};
    given["caustics_window"] = {-5, -5, 10};
    // Light drifts sideways by up to ~1.1 x depth (refraction of a low sun plus the waves'
    // slopes): the grid and the reference's photons reach that far beyond the window.
    const double margin = caustics_margin(o.depth);

    std::vector<CausticsBuild> builds;
    for (CausticsMethod m : {CausticsMethod::AreaRatio, CausticsMethod::PhotonSplat}) {
        if (o.method != "both" && o.method != to_string(m)) continue;
        builds.push_back(build_caustics(m, o.waves));
        if (builds.back().ok()) continue;
        for (const Diagnostic& d : builds.back().diagnostics)
            std::fprintf(stderr, "%s\n", format_diagnostic(d).c_str());
        return kFailed;
    }
    // Both passes read the same wave, sun and window parameters with the same defaults.
    CausticsSetup setup =
        caustics_reference_setup(o.waves, caustics_values(builds.front(), given), o.size, margin);
    setup.photons_per_side = 8;
    std::string error;
    const CausticsImage reference = caustics_reference(setup, &error);
    if (!error.empty()) {
        std::fprintf(stderr, "watergen: error: reference: %s\n", error.c_str());
        return kUsage;
    }
    std::string cache;
    auto runner = create_runner(o.runner, &cache);
    if (!runner) return kNoDevice;
    std::vector<MethodResult> results;
    for (const CausticsBuild& build : builds)
        if (!draw_method(*runner, o, build, given, margin, reference, results.emplace_back()))
            return kFailed;

    std::printf("caustics of %s waves on a bottom %g m deep, %ux%u texels over 10 x 10 m, on %s\n",
                o.waves.c_str(), o.depth, o.size, o.size, runner->device_info().name.c_str());
    std::printf("%-13s %10s %8s %10s %10s %9s %8s %11s\n", "method", "steady ms", "mean",
                "unclamped", "clamp lost", "max abs", "RMSE", "GLSL-HLSL");
    std::printf("%-13s %10s %8.4f %10s %10s %9s %8s %11s\n", "reference", "(CPU)", reference.mean(),
                "", "", "", "", "");
    std::map<std::string, std::string> files;
    nlohmann::ordered_json methods = nlohmann::ordered_json::array();
    for (const MethodResult& r : results) {
        const double lost = r.mean_unclamped - r.mean;
        std::printf("%-13s %10.2f %8.4f %10.4f %10.4f %9.4f %8.4f %11.2g\n", to_string(r.method),
                    r.steady_ms, r.mean, r.mean_unclamped, lost, r.max_abs, r.rmse, r.glsl_vs_hlsl);
        methods.push_back({{"method", to_string(r.method)},
                           {"steady_draw_ms", r.steady_ms},
                           {"mean", r.mean},
                           {"mean_unclamped", r.mean_unclamped},
                           {"clamp_lost", lost},
                           {"max_abs_vs_reference", r.max_abs},
                           {"rmse_vs_reference", r.rmse},
                           {"glsl_vs_hlsl", r.glsl_vs_hlsl}});
        files[std::string(to_string(r.method)) + ".png"] = png(r.intensity, o.size, &error);
        if (!error.empty()) break;
    }
    files["reference.png"] = png(reference.intensity, o.size, &error);
    if (!error.empty()) {
        std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
        return kFailed;
    }
    const nlohmann::ordered_json doc = {{"waves", o.waves},
                                        {"depth", o.depth},
                                        {"clamp", o.clamp},
                                        {"texels", o.size},
                                        {"window", {-5, -5, 10}},
                                        {"reference_mean", reference.mean()},
                                        {"device", runner->device_info().name},
                                        {"methods", methods}};
    files["caustics.json"] = doc.dump(2) + "\n";
    const std::filesystem::path dir = std::filesystem::path(o.out) / ("caustics-" + o.waves);
    if (auto e = write_directory_atomically(dir, files)) {
        std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
        return kFailed;
    }
    std::printf("intensity relative to flat water; clamp lost = unclamped mean - mean; error "
                "against the CPU photon reference (%u photons per texel); wrote %s\n",
                setup.photons_per_side * setup.photons_per_side, dir.string().c_str());
    return kOk;
}

} // namespace

Runner add_caustics_command(CLI::App& app, const Common&) {
    auto o = std::make_shared<Options>();
    app.add_option("--waves", o->waves, "wave model: sum_of_sines or gerstner (default gerstner)")
        ->check(CLI::IsMember({"sum_of_sines", "gerstner"}));
    app.add_option("--method", o->method, "area_ratio, photon_splat or both (default both)")
        ->check(CLI::IsMember({"area_ratio", "photon_splat", "both"}));
    std::vector<std::string> names;
    for (const Preset& p : presets())
        names.push_back(p.name);
    app.add_option("--preset", o->preset, "parameter preset (its sun): " + preset_names())
        ->check(CLI::IsMember(names));
    app.add_option("--depth", o->depth, "bottom depth below the water level, m (default 3)")
        ->check(finite_range(0, 1000));
    app.add_option("--clamp", o->clamp, "area ratio clamp (default 5, as HDRP)")
        ->check(finite_range(0, 1e30));
    app.add_option("--size", o->size, "texture side in texels (default 256, the seed's)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--cells", o->cells,
                   "grid cells (photons) per texel side (default 2 for area_ratio, 8 for "
                   "photon_splat)")
        ->check(CLI::Range(1, 32));
    app.add_option("--draws", o->draws, "timed draws per method (default 5)")
        ->check(CLI::Range(1, 100));
    app.add_option("--out", o->out, "directory for caustics-<waves>/ (default out/caustics)");
    add_runner_options(app, o->runner);
    return [o]() { return run(*o); };
}

} // namespace watergen::cli
