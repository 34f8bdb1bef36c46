// Unroll bench: kept loops against unrolled ones on lavapipe, per waves choice.
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/eval/bench/unroll_bench.h"
#include "watergen/pipeline/compile_bench.h"

namespace watergen::cli {

namespace {

std::string range_text(const std::vector<double>& v) {
    if (v.empty()) return "-";
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return fmt::format("{:.2f} ({:.2f}-{:.2f})", median(v), *lo, *hi);
}

nlohmann::ordered_json side_json(const UnrollSide& s) {
    return {{"glsl_lines", s.glsl_lines},         {"spirv_words", s.spirv_words},
            {"instructions", s.instructions},     {"first_draw_ms", s.first_draw_ms},
            {"steady_draw_ms", s.steady_draw_ms}, {"pipeline_ms", s.pipeline_ms}};
}

void print_table(const UnrollBench& b) {
    std::printf("unroll bench: %ux%u, %u rounds, each sample one language path of one render\n",
                b.size, b.size, b.rounds);
    std::printf("%-26s %11s %13s %9s %9s %22s %22s %9s %9s %22s %22s\n", "waves", "lines k/u",
                "instr k/u", "first k", "first u", "first u/k", "first A/A", "steady k", "steady u",
                "steady u/k", "steady A/A");
    for (const auto& r : b.rows)
        std::printf("%-26s %5zu/%-5zu %6zu/%-6zu %9.1f %9.1f %22s %22s %9.3f %9.3f %22s %22s\n",
                    r.waves.c_str(), r.kept.glsl_lines, r.unrolled.glsl_lines, r.kept.instructions,
                    r.unrolled.instructions, median(r.kept.first_draw_ms),
                    median(r.unrolled.first_draw_ms), range_text(r.first_draw_ratio).c_str(),
                    range_text(r.first_draw_aa).c_str(), median(r.kept.steady_draw_ms),
                    median(r.unrolled.steady_draw_ms), range_text(r.steady_ratio).c_str(),
                    range_text(r.steady_aa).c_str());
    std::printf("k: every loop [[dont_unroll]] / [loop]; u: every loop [[unroll]] / [unroll] "
                "(spirv-opt unrolls). Times in ms, medians; ratios: median (min-max) over "
                "rounds and paths; A/A: the kept shader against itself.\n");
}

} // namespace

Runner add_bench_unroll_command(CLI::App& app, const Common& common) {
    struct Options {
        uint32_t size = 256, rounds = 3, draws = 5;
        std::string out = "out/bench";
        RunnerSetup runner;
    };
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--rounds", o->rounds, "interleaved rounds (default 3)")
        ->check(CLI::Range(1, 100));
    app.add_option("--draws", o->draws, "timed draws per render (default 5)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--out", o->out, "directory for unroll.csv and unroll.json (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        const UnrollBench bench = run_unroll_bench(*runner, o->size, o->rounds, o->draws);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        print_table(bench);
        std::string csv = "waves,hint,glsl_lines,spirv_words,instructions,first_draw_ms_median,"
                          "steady_draw_ms_median,first_draw_ratio_median,steady_ratio_median\n";
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        for (const auto& r : bench.rows) {
            for (const auto& [hint, side] :
                 {std::pair{"kept", &r.kept}, std::pair{"unrolled", &r.unrolled}})
                csv += fmt::format("{},{},{},{},{},{:.3f},{:.4f},{:.4f},{:.4f}\n", r.waves, hint,
                                   side->glsl_lines, side->spirv_words, side->instructions,
                                   median(side->first_draw_ms), median(side->steady_draw_ms),
                                   median(r.first_draw_ratio), median(r.steady_ratio));
            rows.push_back({{"waves", r.waves},
                            {"kept", side_json(r.kept)},
                            {"unrolled", side_json(r.unrolled)},
                            {"kept_again", side_json(r.kept_again)},
                            {"first_draw_ratio", r.first_draw_ratio},
                            {"first_draw_aa", r.first_draw_aa},
                            {"steady_ratio", r.steady_ratio},
                            {"steady_aa", r.steady_aa}});
        }
        nlohmann::ordered_json j = {{"size", bench.size},
                                    {"rounds", bench.rounds},
                                    {"draws", o->draws},
                                    {"device", runner->device_info().name},
                                    {"rows", rows}};
        return write_bench_files(o->out, "unroll", csv, j.dump(2) + "\n") ? kOk : kFailed;
    };
}

} // namespace watergen::cli
