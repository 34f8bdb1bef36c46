// Checks shared by the numeric flags of every subcommand.
#include <cmath>
#include <cstdio>
#include <limits>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/pipeline/jobs/parallel_build.h"
#include "watergen/water/tessellated_mesh.h"

namespace watergen::cli {

CLI::Validator finite_range(double lo, double hi) {
    // CLI::Range lets NaN through (every comparison with NaN is false), and prints its bounds
    // rounded to 6 digits; this one rejects NaN and Inf and prints exact bounds.
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0') return fmt::format("'{}' is not a number", text);
            if (!std::isfinite(v) || v < lo || v > hi)
                return fmt::format("{} is out of range; expected a finite number in [{}, {}]", text,
                                   lo, hi);
            return "";
        },
        fmt::format("FLOAT in [{} - {}]", lo, hi));
}

void add_jobs_option(CLI::App& app, unsigned& jobs, const std::string& help) {
    app.add_option("--jobs,-j", jobs,
                   help + "; at most " + std::to_string(kJobsPerHardwareThread) +
                       " per hardware thread (" + std::to_string(max_jobs()) +
                       " here): more is lowered to that, with a note")
        ->check(CLI::Range(0u, std::numeric_limits<unsigned>::max()));
}

unsigned capped_jobs(unsigned jobs) {
    // Lowered, not refused: the count never changes what is built, so a script's -j written
    // for a bigger machine still runs here; the note says what was used.
    if (jobs <= max_jobs()) return jobs;
    std::fprintf(stderr,
                 "watergen: note: --jobs %u is more than %u per hardware thread; using %u\n", jobs,
                 kJobsPerHardwareThread, max_jobs());
    return max_jobs();
}

void add_unroll_option(CLI::App& app, LoopUnroll& unroll) {
    app.add_option_function<std::string>(
           "--unroll", [&unroll](const std::string& word) { unroll = *parse_loop_unroll(word); },
           "unroll hint of every loop: hinted (each loop's own, default), all ([[unroll]] / "
           "[unroll]) or none ([[dont_unroll]] / [loop])")
        ->check(CLI::IsMember({"hinted", "all", "none"}));
}

void add_view_option(CLI::App& app, std::string& view) {
    std::vector<std::string> names;
    for (const SceneView& v : scene_views())
        names.push_back(v.name);
    std::string help = "view of the synthetic scene (default beach):";
    for (const SceneView& v : scene_views())
        help += "\n  " + v.name + ": " + v.description;
    app.add_option("--view", view, help)->check(CLI::IsMember(names));
}

void add_grid_options(CLI::App& app, WaterGridDesc& grid) {
    // Ranges are checked as a whole by check_grid (water_grid_error knows the vertex cap).
    app.add_option("--grid-spacing", grid.spacing,
                   "a mesh variant's finest grid cell, m (default 0.5; the grid is a clipmap "
                   "around the eye, each level twice as coarse as the one inside it)");
    app.add_option("--grid-rings", grid.ring_cells,
                   "cells from a level's centre to its edge (default 32, even, 16 to 512): the "
                   "grid's density at every distance, about rings / distance cells per metre");
    app.add_option("--grid-levels", grid.levels, "clipmap levels (default 8, 1 to 16)");
}

CLI::Option* add_tess_max_option(CLI::App& app, double& tess_max) {
    return app
        .add_option("--tess-max", tess_max,
                    "a tessellated variant's largest tessellation factor (its tess_max "
                    "parameter, 1 to 64; default: the parameter's default)")
        ->check(finite_range(1.0, kMaxTessellationFactor));
}

void note_unused_tess_max(const CLI::Option* option, const Variant& variant) {
    if (option->count() > 0 && variant.choice("geometry") != "tessellated")
        std::fprintf(stderr,
                     "watergen: note: --tess-max: geometry=%s is not tessellated; ignored\n",
                     variant.choice("geometry").c_str());
}

bool check_grid(const WaterGridDesc& grid) {
    if (auto why = water_grid_error(grid)) {
        std::fprintf(stderr, "watergen: error: --grid-*: %s\n", why->c_str());
        return false;
    }
    return true;
}

void add_instrument_options(CLI::App& app, uint32_t& draws, uint32_t& cost_size, bool& cost) {
    app.add_option("--draws", draws, "timed draws per variant and round (default 3)")
        ->check(CLI::Range(1, 100));
    app.add_option("--cost-size", cost_size,
                   "image size of the instruction count under valgrind (default 64)")
        ->check(CLI::Range(8, 512));
    app.add_flag("!--no-cost", cost,
                 "skip the instruction count (valgrind: about 5 s of JIT per variant, two "
                 "workers at once)");
}

} // namespace watergen::cli
