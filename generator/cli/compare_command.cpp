// `watergen compare`: variants side by side against one reference (compare_setup.h,
// compare_and_report.h), with draw times (interleaved, A/A-checked) and the load-free cost
// (valgrind instruction counts).
#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "commands.h"
#include "watergen/eval/compare/compare_and_report.h"
#include "watergen/eval/report/compare_report.h"
#include "watergen/eval/scene/scene_views.h"
#include "watergen/ir/core/text.h"

namespace watergen::cli {

namespace {

struct CompareOptions {
    CompareSpec spec;
    RunnerSetup runner;
};

// The choices where `v` differs from `base`, "fresnel=schlick extinction=linear", or "(same)".
std::string differences(const Variant& v, const Variant& base) {
    std::string out;
    const auto& list = axes();
    for (size_t a = 0; a < list.size(); ++a)
        if (v.choices[a] != base.choices[a])
            out += (out.empty() ? "" : " ") + list[a].name + "=" + v.choices[a];
    return out.empty() ? "(the reference)" : out;
}

void print_table(const CompareRun& run, const CompareSetup& setup) {
    std::printf("reference: %s%s\n", run.reference.key().c_str(),
                run.reference_on_cpu ? " (CPU, double)" : " (GPU)");
    std::printf("%-44s %-12s %24s %12s", "variant (differs from the reference in)", "relation",
                "time ratio [95% CI]", "cost/pixel");
    for (const GpuTarget& t : setup.gpu_targets)
        std::printf(" %10s", t.name.c_str());
    std::printf(" %8s", "SPIR-V");
    for (const auto& [view, scene] : setup.views)
        std::printf(" %22s", (view + " max|dE p99").c_str());
    std::printf("\n");
    for (const CompareEntry& e : run.entries) {
        const std::string relation = e.relation.substr(0, e.relation.find(' '));
        char time[64];
        std::snprintf(time, sizeof time, "%.3f [%.3f, %.3f]", e.time.ratio, e.time.lo, e.time.hi);
        // 0: not measured (--no-cost), a dash as in the report, never a cost of 0.
        const std::string cost =
            e.cost_per_pixel > 0 ? fmt::format("{:.1f}", e.cost_per_pixel) : std::string("-");
        std::printf("%-44s %-12s %24s %12s", differences(e.variant, run.reference).c_str(),
                    relation.c_str(), time, cost.c_str());
        for (const GpuTarget& t : setup.gpu_targets) {
            const auto it = e.target_costs.find(t.name);
            if (it == e.target_costs.end())
                std::printf(" %10s", "n/a");
            else
                std::printf(" %10.0f", it->second);
        }
        std::printf(" %8zu", e.spirv_instructions);
        for (const ComparedView& v : e.views)
            std::printf("  %9.3g | %8.3f", v.error.max_abs, v.error.ciede2000_p99);
        std::printf("\n");
    }
    double paths = 0; // GLSL against HLSL, over every variant and view
    for (const CompareEntry& e : run.entries)
        for (const ComparedView& v : e.views)
            paths = std::max(paths, v.glsl_vs_hlsl);
    std::printf("GLSL and HLSL images: %s\n",
                paths == 0 ? "bit-identical in every view"
                           : ("differ by up to " + std::to_string(paths) + " (max abs)").c_str());
    if (run.cost_aa > 0)
        std::printf("A/A (instructions): the reference against a second pipeline of itself "
                    "%.5f\n",
                    run.cost_aa);
    std::printf("A/A: the reference against itself %.3f [%.3f, %.3f]: %s\n", run.aa.ratio,
                run.aa.lo, run.aa.hi,
                run.timing_trustworthy()
                    ? "within +-3%, time ratios can be trusted on this machine"
                    : "NOT within +-3%: time ratios are not trustworthy on this machine now; use "
                      "the cost column (instructions, independent of load)");
}

// The caustics passes' lines.
void print_caustics(const std::vector<ComparedCausticsPass>& passes, const CompareSetup& setup) {
    std::printf("caustics passes in view %s, against the CPU photon reference:\n",
                setup.views.front().first.c_str());
    std::printf("  %-30s %6s %28s %9s %8s %10s\n", "pass", "texels", "draw ms median [min, max]",
                "max abs", "RMSE", "GLSL-HLSL");
    for (const ComparedCausticsPass& c : passes)
        std::printf("  %-30s %6u %8.3f [%8.3f, %8.3f] %9.4f %8.4f %10.3g\n", c.name.c_str(),
                    c.first.texels, c.median_ms, c.min_ms, c.max_ms, c.first.vs_reference.max_abs,
                    c.first.vs_reference.rmse, c.first.glsl_vs_hlsl);
}

int run_compare_command(const CompareOptions& o, const Common& common) {
    if (!check_grid(o.spec.grid)) return kUsage;
    const CompareSetup setup = plan_compare(o.spec);
    print_diagnostics(setup.diagnostics, common);
    for (const std::string& note : setup.notes)
        std::printf("%s\n", note.c_str());
    if (setup.status != RunStatus::Ok) return stop({}, setup.error, setup.status, common);
    std::string cache;
    auto runner = create_runner(o.runner, &cache);
    if (!runner) return kNoDevice;
    if (o.spec.strict_half && !has_float16(*runner, "; strict half needs it")) return kNoDevice;
    const CompareOutcome out = compare_and_report(*runner, setup);
    if (!bench_succeeded(out.diagnostics, out.error, common))
        return out.status == RunStatus::NoDevice ? kNoDevice : kFailed;
    print_table(out.run, setup);
    if (!out.caustics.empty()) print_caustics(out.caustics, setup);
    if (!out.write_error.empty()) {
        std::fprintf(stderr, "watergen: error: %s\n", out.write_error.c_str());
        return kFailed;
    }
    std::printf("wrote %s/%s, %s, %s\n", o.spec.out.c_str(), kCompareReportHtml, kCompareCsv,
                kCompareJson);
    return kOk;
}

} // namespace

Runner add_compare_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<CompareOptions>();
    CompareSpec& s = o->spec;
    const auto& list = axes();
    s.axis_lists.resize(list.size());
    for (size_t a = 0; a < list.size(); ++a)
        app.add_option("--" + list[a].name, s.axis_lists[a],
                       "choices of " + list[a].name + " to compare, comma-separated (default: " +
                           list[a].default_choice + " only)");
    app.add_option("--variant", s.keys, "a variant key to compare (repeatable)");
    app.add_option("--preset", s.preset,
                   "parameter preset, or several comma-separated: each view is rendered under "
                   "each (views named <view>@<preset>)");
    app.add_option("--material", s.material,
                   "compare the variants of this material file (with --scene: its pruned set)");
    app.add_option("--scene", s.scene,
                   "compare the variants this scene file reaches of the material (default: the "
                   "built-in material), built as the scene's build ships them");
    app.add_option("--reference", s.reference,
                   "gold (default): the gold of every axis that varies, on the CPU in double; or a "
                   "variant key, rendered on the GPU");
    app.add_option("--views", s.views,
                   "views to render, comma-separated (default: every view: " + scene_view_names() +
                       "); the first is the one timed")
        ->check([](const std::string& list) -> std::string {
            for (const std::string& name : split(list, ','))
                if (!find_scene_view(name))
                    return "'" + name + "' is not a view (" + scene_view_names() + ")";
            return "";
        });
    app.add_option("--size", s.size, "image width and height (default 512)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--rounds", s.rounds,
                   "timing rounds, interleaved (default 40: at 15, the A/A interval came out wider "
                   "than +-3% in 3 of 5 runs on an idle 2-core machine)")
        ->check(CLI::Range(3, 1000));
    add_instrument_options(app, s.draws, s.cost_size, s.cost);
    add_target_option(app, s.targets);
    add_grid_options(app, s.grid);
    app.add_flag("--strict-half", s.strict_half,
                 "build precision=half variants in explicit 16-bit types, so that lavapipe "
                 "computes them at 16 bits (with the default relaxed-precision hints it computes "
                 "them at 32, and half equals full)");
    app.add_option("--out", s.out, "output directory (default out/compare)");
    add_runner_options(app, o->runner);
    return [o, &common]() { return run_compare_command(*o, common); };
}

} // namespace watergen::cli
