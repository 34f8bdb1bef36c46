// Accuracy bench: on every axis that has a gold choice, each other choice against the gold over
// the named views, with the instrument of `watergen compare`: interleaved draw times with an A/A
// check, instructions per pixel (valgrind), and error for approximations only.
#include <cstdio>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "watergen/eval/bench/accuracy_bench.h"
#include "watergen/eval/scene/scene_views.h"

namespace watergen::cli {

namespace {

struct Options {
    uint32_t size = 256, rounds = 20, draws = 3, cost_size = 64;
    bool cost = true;
    std::string out = "out/bench";
    RunnerSetup runner;
};

// Instructions per pixel of every row's variant, from one valgrind worker; false on failure.
bool add_costs(const Options& o, AccuracyBench& bench) {
    std::vector<Variant> variants;
    std::set<std::string> keys;
    for (const AccuracyRow& r : bench.rows)
        if (!r.skipped() && keys.insert(r.variant.key()).second) variants.push_back(r.variant);
    std::string error;
    const auto counts = count_draw_costs(variants, o.cost_size, "", "beach", &error, true);
    if (!counts) {
        std::fprintf(stderr, "watergen: error: instruction count: %s\n", error.c_str());
        return false;
    }
    for (AccuracyRow& r : bench.rows)
        if (auto it = counts->find(r.variant.key()); it != counts->end())
            r.cost_per_pixel = double(it->second) / (double(o.cost_size) * o.cost_size);
    return true;
}

double gold_cost(const AccuracyBench& bench, const std::string& axis) {
    for (const AccuracyRow& r : bench.rows)
        if (r.axis == axis && r.gold) return r.cost_per_pixel;
    return 0;
}

void print_rows(const AccuracyBench& bench) {
    std::printf("%-11s %-26s %-13s %10s %7s %22s %9s %10s  %s\n", "axis", "choice", "relation",
                "cost/px", "cost", "time [95% CI]", "max abs", "dE p99", "worst view");
    for (const AccuracyRow& r : bench.rows) {
        const std::string choice = r.choice + (r.gold ? " (gold)" : "");
        if (r.skipped()) {
            std::printf("%-11s %-26s %s\n", r.axis.c_str(), choice.c_str(), r.note.c_str());
            continue;
        }
        const double g = gold_cost(bench, r.axis);
        const std::string time =
            fmt::format("{:.3f} [{:.3f}, {:.3f}]", r.time.ratio, r.time.lo, r.time.hi);
        const std::string kind = r.relation.substr(0, r.relation.find(' '));
        if (r.gold || r.approximation())
            std::printf("%-11s %-26s %-13s %10.1f %6.3fx %22s %9.3g %10.3f  %s\n", r.axis.c_str(),
                        choice.c_str(), kind.c_str(), r.cost_per_pixel,
                        g > 0 ? r.cost_per_pixel / g : 0.0, time.c_str(), r.worst.max_abs,
                        r.worst.ciede2000_p99, r.worst_view.c_str());
        else // a different model: its cost, not an error
            std::printf("%-11s %-26s %-13s %10.1f %6.3fx %22s %20s\n", r.axis.c_str(),
                        choice.c_str(), "different", r.cost_per_pixel,
                        g > 0 ? r.cost_per_pixel / g : 0.0, time.c_str(), "(different model)");
    }
    for (const AccuracyAxis& a : bench.axes)
        std::printf("A/A %-11s %.3f [%.3f, %.3f]%s\n", a.axis.c_str(), a.aa.ratio, a.aa.lo, a.aa.hi,
                    a.aa.within(kAATolerance) ? "" : "  NOT within +-3%: times untrusted");
}

std::string bench_files(const AccuracyBench& bench, nlohmann::ordered_json& json) {
    std::string csv = "axis,choice,gold,relation,cost_per_pixel,time_ratio,time_lo,time_hi,"
                      "spirv_instructions,max_abs,rmse,ciede2000_mean,ciede2000_p99,worst_view,"
                      "note\n";
    for (const AccuracyRow& r : bench.rows) {
        const bool error = r.gold || r.approximation();
        csv += fmt::format("{},{},{},\"{}\",{:.2f},{:.4f},{:.4f},{:.4f},{},{},{},{},{},{},\"{}\"\n",
                           r.axis, r.choice, r.gold, r.relation, r.cost_per_pixel, r.time.ratio,
                           r.time.lo, r.time.hi, r.spirv_instructions,
                           error ? fmt::format("{:.6g}", r.worst.max_abs) : "",
                           error ? fmt::format("{:.6g}", r.worst.rmse) : "",
                           error ? fmt::format("{:.4f}", r.worst.ciede2000_mean) : "",
                           error ? fmt::format("{:.4f}", r.worst.ciede2000_p99) : "",
                           error ? r.worst_view : "", r.note);
        nlohmann::ordered_json row = {{"axis", r.axis},
                                      {"choice", r.choice},
                                      {"gold", r.gold},
                                      {"relation", r.relation},
                                      {"cost_per_pixel", r.cost_per_pixel},
                                      {"time_ratio", {r.time.ratio, r.time.lo, r.time.hi}},
                                      {"spirv_instructions", r.spirv_instructions},
                                      {"note", r.note}};
        if (error)
            row["error"] = {{"max_abs", r.worst.max_abs},
                            {"rmse", r.worst.rmse},
                            {"ciede2000_mean", r.worst.ciede2000_mean},
                            {"ciede2000_p99", r.worst.ciede2000_p99},
                            {"worst_view", r.worst_view}};
        json.push_back(row);
    }
    return csv;
}

} // namespace

Runner add_bench_accuracy_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<Options>();
    app.add_option("--size", o->size, "image width and height (default 256)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--rounds", o->rounds, "timing rounds, interleaved (default 20)")
        ->check(CLI::Range(3, 1000));
    add_instrument_options(app, o->draws, o->cost_size, o->cost);
    app.add_option("--out", o->out,
                   "directory for accuracy.csv and accuracy.json (default out/bench)");
    add_runner_options(app, o->runner);
    return [o, &common]() {
        std::string cache;
        auto runner = create_runner(o->runner, &cache);
        if (!runner) return kNoDevice;
        std::vector<std::pair<std::string, SyntheticScene>> views;
        for (const SceneView& v : scene_views())
            views.emplace_back(v.name, make_synthetic_scene(o->size, o->size, v));
        AccuracyBench bench = run_accuracy_bench(*runner, views, o->rounds, o->draws);
        if (!bench_succeeded(bench.diagnostics, bench.error, common)) return kFailed;
        if (o->cost && !add_costs(*o, bench)) return kFailed;
        print_rows(bench);
        std::printf("reference: %s; %ux%u over %zu views, %u rounds x %u draws, %s; cost: "
                    "instructions per pixel, %ux%u beach view\n",
                    accuracy_reference_variant().key().c_str(), o->size, o->size, views.size(),
                    o->rounds, o->draws, runner->device_info().name.c_str(), o->cost_size,
                    o->cost_size);
        nlohmann::ordered_json rows = nlohmann::ordered_json::array();
        const std::string csv = bench_files(bench, rows);
        nlohmann::ordered_json doc = {{"reference", accuracy_reference_variant().key()},
                                      {"size", o->size},
                                      {"views", bench.views},
                                      {"rounds", o->rounds},
                                      {"draws", o->draws},
                                      {"device", runner->device_info().name},
                                      {"rows", rows}};
        if (!write_bench_files(o->out, "accuracy", csv, doc.dump(2) + "\n")) return kFailed;
        return kOk;
    };
}

} // namespace watergen::cli
