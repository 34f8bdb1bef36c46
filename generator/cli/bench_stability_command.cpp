// Stability bench: prints run_stability_bench() (eval/bench/stability_bench.h) row by row and
// writes stability.csv, stability.json and stability.html; exits 1 when a point within the
// corner (time and distance) is more than --max-ratio times its case's figure at the origin
// (stability_row_within: max abs, dE00 p99, strict half).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/bench/stability_bench.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/water/axis_registry.h"

namespace watergen::cli {

namespace {

void print_row(const StabilityRow& r) {
    std::printf("%-16s %-5s %-11s %5u %-9s %-10s %10.4g %10.4g %5.3g %9.3g %9.3g %8.3g %6llu",
                r.what.waves.c_str(), r.what.precision.c_str(), r.what.geometry.c_str(),
                r.what.size, r.where.sweep.c_str(), r.where.view.c_str(), r.where.time,
                r.where.offset, r.where.elevation, r.max_abs[0], r.max_abs[1], r.de00_p99[0],
                static_cast<unsigned long long>(r.over_bound[0] + r.over_bound[1]));
    std::printf(" %9.3g %6llu", r.continuous.max_abs,
                static_cast<unsigned long long>(r.continuous.discontinuous));
    if (std::isfinite(r.before.max_abs)) std::printf("  before %.4g", r.before.max_abs);
    // A half case in 16-bit arithmetic against the CPU's half model.
    if (std::isfinite(r.strict_max_abs))
        std::printf("  strict half %.3g (%lld ulps)", r.strict_max_abs,
                    static_cast<long long>(r.strict_max_ulps));
    std::printf("\n");
    std::fflush(stdout);
}

// Every waves choice but the flat plane: the families the sweep runs by default.
std::vector<std::string> wave_families() {
    std::vector<std::string> out;
    if (const AxisInfo* waves = find_axis("waves"))
        for (const ChoiceInfo& c : waves->choices)
            if (c.name != "flat") out.push_back(c.name);
    return out;
}

} // namespace

Runner add_bench_stability_command(CLI::App& app, const Common& common) {
    struct Options {
        std::vector<std::string> waves = wave_families();
        std::vector<std::string> precision = {"full", "half"};
        std::vector<std::string> geometry = {"screen_pass", "mesh", "tessellated"};
        std::vector<uint32_t> sizes = {512};
        std::vector<double> times = default_stability_times();
        std::vector<double> offsets = default_stability_offsets();
        std::vector<double> elevations = default_stability_elevations();
        double corner_time = 604800, corner_offset = 1e5, max_ratio = 2.0;
        std::string out = "out/bench", before;
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    app.add_option("--waves", o->waves, "waves choices (default: every one but flat)")
        ->delimiter(',');
    app.add_option("--precision", o->precision, "precision choices (default full,half)")
        ->delimiter(',');
    app.add_option("--geometry", o->geometry,
                   "geometry choices (default screen_pass,mesh,tessellated)")
        ->delimiter(',');
    app.add_option("--sizes", o->sizes,
                   "image sizes, width = height (default 512; the issue's "
                   "full sweep adds 1024)")
        ->delimiter(',')
        ->check(CLI::Range(16, 2048));
    app.add_option("--times", o->times,
                   "times of the time sweep in s (default 0,3600,86400,604800,31557600)")
        ->delimiter(',')
        ->check(finite_range(0, 1e9));
    app.add_option("--offsets", o->offsets,
                   "distances from the world origin of the distance sweep in m (default "
                   "0,1e3,1e4,1e5,1e6)")
        ->delimiter(',')
        ->check(finite_range(0, 1e7));
    app.add_option("--elevations", o->elevations,
                   "pitches below the horizon of the grazing view in degrees (default 10,3,1,0.5)")
        ->delimiter(',')
        ->check(finite_range(0.1, 89));
    app.add_option("--corner-time", o->corner_time,
                   "the far corner's time, every view drawn there (default 604800, a week)")
        ->check(finite_range(0, 1e9));
    app.add_option("--corner-offset", o->corner_offset,
                   "the far corner's distance from the origin in m (default 1e5)")
        ->check(finite_range(0, 1e7));
    app.add_option("--max-ratio", o->max_ratio,
                   "exit 1 when a point no later and no further than the corner has more than "
                   "this times its case's max abs or dE00 p99 at the origin, past the floors "
                   "1e-5 and 0.01 (default 2)")
        ->check(finite_range(1, 1e9));
    app.add_option("--before", o->before,
                   "a stability.csv from before a change (an earlier commit's bench): each row "
                   "shows its case and point's figure from there beside this run's");
    app.add_option("--out", o->out,
                   "directory for stability.csv, .json and .html (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        std::vector<StabilityCase> cases;
        for (uint32_t size : o->sizes)
            for (const std::string& w : o->waves)
                for (const std::string& p : o->precision)
                    for (const std::string& g : o->geometry) {
                        StabilityCase c{w, p, g, size};
                        std::string error;
                        if (!stability_variant(c, error)) return stop(error, RunStatus::BadInput);
                        cases.push_back(c);
                    }
        std::optional<StabilityBeforeTable> before;
        if (!o->before.empty()) {
            std::string error;
            before = read_stability_before(o->before, error);
            if (!before) return stop(error, RunStatus::BadInput);
        }
        const std::vector<StabilityPoint> points =
            stability_points(o->times, o->offsets, o->elevations, o->corner_time, o->corner_offset);
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        std::printf("%zu cases x %zu points on %s; GPU against the CPU in double\n", cases.size(),
                    points.size(), runner->device_info().name.c_str());
        std::printf("%-16s %-5s %-11s %5s %-9s %-10s %10s %10s %5s %9s %9s %8s %6s %9s %6s\n",
                    "waves", "prec", "geometry", "size", "sweep", "view", "time s", "offset m",
                    "elev", "glsl max", "hlsl max", "dE00 p99", ">bound", "cont max", "disc");
        const auto start = std::chrono::steady_clock::now();
        const StabilityBench bench =
            run_stability_bench(*runner, cases, points, &print_row, before ? &*before : nullptr);
        if (!bench_succeeded({}, bench.error, common)) return kFailed;
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!runner->device_info().shader_float16)
            for (const StabilityCase& c : cases)
                if (c.precision == "half" && c.geometry == "screen_pass") {
                    std::printf("note: %s has no shaderFloat16: the half cases were drawn in "
                                "relaxed precision only, not in 16-bit arithmetic\n",
                                runner->device_info().name.c_str());
                    break;
                }
        size_t over = 0;
        for (const StabilityRow& r : bench.rows)
            if (r.where.time <= o->corner_time && r.where.offset <= o->corner_offset &&
                !stability_row_within(r, o->max_ratio))
                ++over;
        std::printf("%zu rows in %.0f s; %zu within the corner (%g s, %g m) over %g x their "
                    "figure at the origin\n",
                    bench.rows.size(), seconds, over, o->corner_time, o->corner_offset,
                    o->max_ratio);
        if (!write_bench_files(o->out, "stability", bench.csv, bench.json)) return kFailed;
        const std::filesystem::path html = std::filesystem::path(o->out) / "stability.html";
        if (auto e = write_file_atomically(html, bench.html)) {
            std::fprintf(stderr, "watergen: error: %s\n", e->c_str());
            return kFailed;
        }
        std::printf("wrote %s\n", html.string().c_str());
        return over == 0 ? kOk : kFailed;
    };
}

} // namespace watergen::cli
