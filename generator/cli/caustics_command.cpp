// `watergen caustics`: the caustics passes (area ratio, photon splatting) drawn on the Vulkan
// runner for one wave model, against the CPU photon reference (caustics_comparison.h): the
// textures as PNG images, the pass time on the device, each method's error against the
// reference, and the light the clamp loses. Writes <out>/caustics-<waves>/ whole.
#include <cstdio>

#include "commands.h"
#include "watergen/eval/report/caustics_comparison.h"

namespace watergen::cli {

namespace {

struct Options {
    CausticsComparisonRequest request;
    std::string preset, out = "out/caustics";
    RunnerSetup runner;
};

void print_table(const CausticsComparisonSetup& setup, const CausticsComparison& c,
                 const VulkanRunner& runner) {
    const CausticsComparisonRequest& o = setup.request;
    std::printf("caustics of %s waves on a bottom %g m deep, %ux%u texels over 10 x 10 m, on %s\n",
                o.waves.c_str(), o.depth, o.size, o.size, runner.device_info().name.c_str());
    std::printf("%-13s %10s %8s %10s %10s %9s %8s %11s\n", "method", "steady ms", "mean",
                "unclamped", "clamp lost", "max abs", "RMSE", "GLSL-HLSL");
    std::printf("%-13s %10s %8.4f %10s %10s %9s %8s %11s\n", "reference", "(CPU)",
                setup.reference.mean(), "", "", "", "", "");
    for (const CausticsMethodFigures& r : c.methods)
        std::printf("%-13s %10.2f %8.4f %10.4f %10.4f %9.4f %8.4f %11.2g\n", to_string(r.method),
                    r.steady_ms, r.mean, r.mean_unclamped, r.clamp_lost(), r.max_abs, r.rmse,
                    r.glsl_vs_hlsl);
}

int run(Options& o) {
    o.request.preset = o.preset.empty() ? nullptr : find_preset(o.preset);
    o.request.out = o.out;
    const CausticsComparisonSetup setup = prepare_caustics_comparison(o.request);
    // The passes' diagnostics in the default format, as this command always printed them.
    for (const Diagnostic& d : setup.diagnostics)
        std::fprintf(stderr, "%s\n", format_diagnostic(d).c_str());
    if (setup.status != RunStatus::Ok) return stop({}, setup.error, setup.status, Common{});
    std::string cache;
    auto runner = create_runner(o.runner, &cache);
    if (!runner) return kNoDevice;
    const CausticsComparison c = run_caustics_comparison(*runner, setup);
    if (c.status != RunStatus::Ok) return stop({}, c.error, c.status, Common{});
    print_table(setup, c, *runner);
    std::printf("intensity relative to flat water; clamp lost = unclamped mean - mean; error "
                "against the CPU photon reference (%u photons per texel); wrote %s\n",
                setup.reference_setup.photons_per_side * setup.reference_setup.photons_per_side,
                c.dir.string().c_str());
    return kOk;
}

} // namespace

Runner add_caustics_command(CLI::App& app, const Common&) {
    auto o = std::make_shared<Options>();
    CausticsComparisonRequest& r = o->request;
    app.add_option("--waves", r.waves, "wave model: sum_of_sines or gerstner (default gerstner)")
        ->check(CLI::IsMember({"sum_of_sines", "gerstner"}));
    app.add_option("--method", r.method, "area_ratio, photon_splat or both (default both)")
        ->check(CLI::IsMember({"area_ratio", "photon_splat", "both"}));
    std::vector<std::string> names;
    for (const Preset& p : presets())
        names.push_back(p.name);
    app.add_option("--preset", o->preset, "parameter preset (its sun): " + preset_names())
        ->check(CLI::IsMember(names));
    app.add_option("--depth", r.depth, "bottom depth below the water level, m (default 3)")
        ->check(finite_range(0, 1000));
    app.add_option("--clamp", r.clamp, "area ratio clamp (default 5, as HDRP)")
        ->check(finite_range(0, 1e30));
    app.add_option("--size", r.size, "texture side in texels (default 256, the seed's)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--cells", r.cells,
                   "grid cells (photons) per texel side (default 2 for area_ratio, 8 for "
                   "photon_splat)")
        ->check(CLI::Range(1, 32));
    app.add_option("--draws", r.draws, "timed draws per method (default 5)")
        ->check(CLI::Range(1, 100));
    app.add_option("--out", o->out, "directory for caustics-<waves>/ (default out/caustics)");
    add_runner_options(app, o->runner);
    return [o]() { return run(*o); };
}

} // namespace watergen::cli
