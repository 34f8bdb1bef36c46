// Geometry bench: prints run_geometry_bench() (eval/bench/geometry_bench.h) as a table per view
// and writes it to geometry.csv and geometry.json.
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/bench/geometry_bench.h"

namespace watergen::cli {

namespace {

// Millions, or "-" for a value not measured.
std::string millions(double v) {
    return v > 0 ? fmt::format("{:.1f}", v / 1e6) : "-";
}

void print_view(const GeometryBench& bench, const std::string& view) {
    std::printf("\n%s\n%-12s %6s %9s %10s %10s %9s %8s %9s %17s %8s %18s %9s", view.c_str(),
                "geometry", "rings", "tess_max", "vertices", "primitives", "max abs", "dE mean",
                "dE p99", "morph: share p99", "draw ms", "draw / screen pass", "lvp Minst");
    for (const TargetCosts& t : bench.aco)
        std::printf(" %12s", (t.run.target.name + " Minst").c_str());
    std::printf("\n");
    for (const GeometryBenchRow& r : bench.rows) {
        if (r.view != view) continue;
        const bool mesh = r.geometry != "screen_pass";
        const std::string morph =
            mesh ? fmt::format("{:5.1f}% {:6.2f}", 100 * r.morph_share, r.morph_p99) : "-";
        std::printf("%-12s %6s %9s %10llu %10llu %9.3g %8.3f %9.3f %17s %8.2f %6.2f [%.2f, %.2f] "
                    "%9s",
                    r.geometry.c_str(), mesh ? std::to_string(r.grid.ring_cells).c_str() : "-",
                    r.tess_max > 0 ? std::to_string(int(r.tess_max)).c_str() : "-",
                    static_cast<unsigned long long>(r.vertices),
                    static_cast<unsigned long long>(r.primitives), r.vs_exact.max_abs,
                    r.vs_exact.ciede2000_mean, r.vs_exact.ciede2000_p99, morph.c_str(), r.draw_ms,
                    r.draw_time.ratio, r.draw_time.lo, r.draw_time.hi,
                    millions(double(r.instructions)).c_str());
        for (const TargetCosts& t : bench.aco) {
            const auto it = r.aco_frame.find(t.run.target.name);
            std::printf(" %12s", millions(it == r.aco_frame.end() ? 0 : it->second).c_str());
        }
        std::printf("\n");
    }
    if (const auto aa = bench.timing_aa.find(view); aa != bench.timing_aa.end())
        std::printf("draw-time A/A (the screen pass against a second pipeline of itself): %.3f "
                    "[%.3f, %.3f]%s\n",
                    aa->second.ratio, aa->second.lo, aa->second.hi,
                    aa->second.within(kAATolerance) ? "" : ": NOT within +-3%");
    if (const auto aa = bench.count_aa.find(view); aa != bench.count_aa.end())
        std::printf("instruction counts' A/A (the screen pass' second pipeline): %.4f%%\n",
                    100.0 * aa->second);
    const uint32_t rings = rings_within(bench, view, 2.0);
    if (rings)
        std::printf("coarsest mesh within CIEDE2000 p99 <= 2: %u rings\n", rings);
    else
        std::printf("no mesh measured within CIEDE2000 p99 <= 2\n");
}

} // namespace

Runner add_bench_geometry_command(CLI::App& app, const Common& common) {
    struct Options {
        GeometryBenchSettings settings;
        Variant variant = default_variant();
        std::string preset, out = "out/bench";
        RunnerSetup runner;
        std::vector<std::string> targets;
    };
    auto o = std::make_shared<Options>();
    // The default: Gerstner waves with their analytic normals, the rest watergen's defaults.
    set_choice(o->variant, "waves", "gerstner");
    set_choice(o->variant, "normals", "analytic");
    add_variant_options(app, o->variant, o->preset);
    app.add_option("--size", o->settings.size, "image width and height (default 512)")
        ->check(CLI::Range(16, 4096));
    app.add_option("--views", o->settings.views, "views of the synthetic scene (default: all)");
    app.add_option("--rings", o->settings.rings,
                   "the meshes' ring counts (default 16 32 64 128 256): even, 16 to 512, with "
                   "the bench's 10 levels at most 4,194,304 vertices a grid (up to 366)")
        ->check(CLI::Range(16, 512));
    app.add_option("--rounds", o->settings.rounds, "interleaved timing rounds (default 5)")
        ->check(CLI::Range(1, 100));
    app.add_option("--out", o->out,
                   "directory for geometry.csv and geometry.json "
                   "(default out/bench)");
    app.add_flag("--count", o->settings.count,
                 "also count the instructions lavapipe executes for each steady draw under "
                 "valgrind (a cost load does not move; minutes at 512x512)");
    app.add_option("--target", o->targets,
                   "AMD families whose ACO statistics to take (RADV's null device, no GPU "
                   "needed): " +
                       gpu_target_names())
        ->take_all();
    add_runner_options(app, o->runner);
    return [o, &common]() {
        const Preset* preset = nullptr;
        if (!resolve_variant(o->variant, o->preset, &preset, common)) return kUsage;
        if (preset) {
            std::fprintf(stderr, "watergen: error: bench geometry draws the views' own values; "
                                 "leave out --preset\n");
            return kUsage;
        }
        // Each grid as the renders check theirs, before a device opens.
        for (uint32_t rings : o->settings.rings)
            if (auto why = water_grid_error({o->settings.spacing, rings, o->settings.levels})) {
                std::fprintf(stderr, "watergen: error: --rings %u: %s\n", rings, why->c_str());
                return kUsage;
            }
        for (const std::string& v : o->settings.views)
            if (!find_scene_view(v)) {
                std::fprintf(stderr, "watergen: error: --views: no view '%s'\n", v.c_str());
                return kUsage;
            }
        if (!o->targets.empty()) {
            const auto targets = resolve_targets(o->targets);
            if (!targets) return kUsage;
            if (has_lavapipe(*targets)) {
                std::fprintf(stderr, "watergen: error: --target: lavapipe's cost is --count\n");
                return kUsage;
            }
            o->settings.targets = amd_targets(*targets);
        }
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const GeometryBench bench = run_geometry_bench(*runner, o->variant, o->settings);
        if (!bench_succeeded({}, bench.error, common)) return bench.no_device ? kNoDevice : kFailed;
        std::printf("%s at %ux%u on %s; errors against the exact surface (the screen pass, its "
                    "search converged, in double); mesh grids: %.2g m cells, %u levels; "
                    "tessellated: %.2g m patches, 16 rings\n",
                    bench.key.c_str(), o->settings.size, o->settings.size,
                    runner->device_info().name.c_str(), o->settings.spacing, o->settings.levels,
                    o->settings.patch_spacing);
        std::vector<std::string> views;
        for (const GeometryBenchRow& r : bench.rows)
            if (views.empty() || views.back() != r.view) views.push_back(r.view);
        for (const std::string& v : views)
            print_view(bench, v);
        for (const TargetCosts& t : bench.aco) {
            std::printf("\n");
            print_gpu_costs(t);
        }
        if (!bench.aco.empty())
            std::printf("\nMinst per AMD target: vertex instructions x vertices + fragment "
                        "instructions per pixel x covered pixels (ACO); no overdraw or vertex "
                        "reuse, none for tessellation\n");
        if (!bench.timing_trustworthy)
            std::printf("\nwarning: an A/A ratio left 1 +- 3%%: the machine was too busy for "
                        "the draw-time ratios\n");
        std::printf("\ndraw times are lavapipe's (a CPU), not a GPU's\n");
        return write_bench_files(o->out, "geometry", bench.csv, bench.json) ? kOk : kFailed;
    };
}

} // namespace watergen::cli
