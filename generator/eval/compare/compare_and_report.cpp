#include "watergen/eval/compare/compare_and_report.h"

#include <algorithm>
#include <cstdio>
#include <memory>

#include <fmt/core.h>

#include "watergen/eval/draw/mesh_render.h"
#include "watergen/eval/measure/draw_cost.h"
#include "watergen/eval/measure/gpu_cost.h"
#include "watergen/eval/report/compare_report.h"
#include "watergen/pipeline/build/build_output.h"

namespace watergen {

namespace {

CompareRequest compare_request(const CompareSetup& s) {
    CompareRequest request;
    request.variants = s.variants;
    request.preset = s.preset;
    request.reference = s.reference;
    request.rounds = s.spec.rounds;
    request.draws = s.spec.draws;
    request.views = s.views;
    request.grid = s.spec.grid;
    if (s.spec.strict_half)
        request.build = [preset = s.preset](const Variant& v) {
            EmitOptions strict;
            strict.strict_half = true;
            return build_variant(v, preset, strict);
        };
    if (s.from_material) {
        request.build = [&s](const Variant& v) {
            return s.plan ? build_for_scene(s.material, *s.plan, v)
                          : build_shader(s.material.compose(v));
        };
        request.exact_surface = [&s](const Variant& v) {
            return exact_surface_fragment(s.material, s.plan ? &*s.plan : nullptr, v);
        };
    }
    return request;
}

// Fills the variants' cost per pixel and the cost's A/A pair (the reference counted once more,
// on its own pipeline); "" or the failure.
std::string add_costs(const CompareSetup& s, CompareRun& run) {
    const CompareSpec& o = s.spec;
    std::vector<Variant> counted;
    for (const CompareEntry& e : run.entries)
        counted.push_back(e.variant);
    const std::string key = run.reference.key();
    counted.push_back(run.reference);
    if (std::none_of(run.entries.begin(), run.entries.end(),
                     [&](const CompareEntry& e) { return e.variant.key() == key; }))
        counted.push_back(run.reference);
    const std::string& first_view = s.views.front().first;
    std::string error;
    const auto costs =
        s.from_material
            ? count_material_costs(o.material, o.scene, counted, o.cost_size, &error, true, o.grid)
            : count_draw_costs(counted, o.cost_size, s.preset ? s.preset->name : "",
                               first_view.substr(0, first_view.find('@')), &error, o.strict_half,
                               o.grid);
    if (!costs) return "instruction count: " + error;
    const double pixels = double(o.cost_size) * o.cost_size;
    for (CompareEntry& e : run.entries)
        if (auto it = costs->find(e.variant.key()); it != costs->end())
            e.cost_per_pixel = double(it->second) / pixels;
    if (costs->count(key) && costs->count(key + "#2") && costs->at(key) > 0) {
        run.reference_cost_per_pixel = double(costs->at(key)) / pixels;
        run.cost_aa = double(costs->at(key + "#2")) / double(costs->at(key));
    }
    return "";
}

// Each entry's fragment cost per pixel on every AMD target (the GLSL path as compared: the
// same build as the render's; none where the family lacks a feature the shader needs);
// "" or the failure, *no_device when a null device is missing.
std::string add_gpu_costs(const CompareSetup& s, const CompareRequest& request, CompareRun& run,
                          bool* no_device) {
    std::vector<VariantBuild> builds;
    std::vector<std::string> keys;
    for (const CompareEntry& e : run.entries) {
        builds.push_back(request.build ? request.build(e.variant)
                                       : build_variant(e.variant, s.preset));
        keys.push_back(e.variant.key());
    }
    const GlslFragmentCosts costs = glsl_fragment_costs(s.gpu_targets, builds, keys);
    *no_device = costs.no_device;
    if (!costs.ok()) return costs.error;
    for (size_t t = 0; t < costs.costs.size(); ++t)
        for (size_t i = 0; i < run.entries.size(); ++i)
            if (costs.costs[t][i])
                run.entries[i].target_costs[s.gpu_targets[t].name] = *costs.costs[t][i];
    return "";
}

// The report's names, before any image: the views and each variant's key, choices and
// reference flag (what the figures' captions read). Every result is filled as it is rendered.
CompareReport report_skeleton(const CompareRun& run, const CompareSetup& s) {
    CompareReport report;
    report.reference_key = run.reference.key() + (run.reference_on_cpu ? " (CPU, double)" : "");
    for (const auto& [name, scene] : s.views)
        report.views.push_back({name, {}, {}});
    const auto& list = axes();
    for (const CompareEntry& e : run.entries) {
        CompareVariant cv;
        cv.key = e.variant.key();
        for (size_t a = 0; a < list.size(); ++a)
            cv.choices[list[a].name] = e.variant.choices[a];
        cv.reference = e.variant.key() == run.reference.key();
        cv.relation = e.relation;
        cv.views.resize(s.views.size());
        report.variants.push_back(std::move(cv));
    }
    return report;
}

// The images of a run go into `report` as they are rendered (figures and error figures), one
// at a time: compare holds one view's reference and one variant image, not every variant's
// image of every view.
void stream_into(CompareRequest& request, const CompareSetup& setup, CompareReport& report) {
    auto ensure = [&report, &setup](const CompareRun& run) {
        if (!report.variants.empty()) return;
        report = report_skeleton(run, setup);
        report.spool = std::make_shared<FigureSpool>(); // the figures wait on disk
    };
    request.on_reference = [&report, ensure](const CompareRun& run, size_t view,
                                             const ImageRGBA32F& reference) {
        ensure(run);
        report.views[view].reference_figure = reference_figure(report, reference);
    };
    request.on_image = [&report, ensure](const CompareRun& run, size_t entry, size_t view,
                                         const ImageRGBA32F& image, const ImageRGBA32F& reference) {
        ensure(run);
        report.variants[entry].views[view] = figured_view_result(report, entry, image, reference);
    };
}

// The report of a run: its streamed figures, then the table and plots (compare_report.h).
void complete_report(CompareReport& report, const CompareRun& run, const CompareSetup& s) {
    const CompareSpec& o = s.spec;
    report.title = "watergen compare: " + std::to_string(run.entries.size()) + " variants";
    for (size_t k = 0; k < run.entries.size(); ++k) {
        const CompareEntry& e = run.entries[k];
        CompareVariant& cv = report.variants[k];
        cv.time_ratio = e.time.ratio;
        cv.time_ratio_lo = e.time.lo;
        cv.time_ratio_hi = e.time.hi;
        cv.cost = e.cost_per_pixel;
        cv.target_costs = e.target_costs;
        cv.spirv_instructions = e.spirv_instructions;
        for (size_t v = 0; v < e.views.size() && v < cv.views.size(); ++v) {
            cv.views[v].beyond_float_bound = e.views[v].beyond_float_bound;
            cv.views[v].float_bound_max = e.views[v].float_bound_max;
        }
    }
    const auto& [first_view, first_scene] = s.views.front();
    char note[400];
    std::snprintf(note, sizeof note,
                  "steady draw time on lavapipe (GLSL path, view %s, %ux%u), interleaved: %u "
                  "rounds x %u draws, the first (JIT) draw excluded; ratio = median over rounds, "
                  "95%% paired bootstrap interval. A/A (the reference against a second pipeline "
                  "of itself): %.3f [%.3f, %.3f]%s",
                  first_view.c_str(), first_scene.width, first_scene.height, o.rounds, o.draws,
                  run.aa.ratio, run.aa.lo, run.aa.hi,
                  run.timing_trustworthy() ? ", within +-3%"
                                           : ": NOT within +-3%, times are not trustworthy on "
                                             "this machine now; use the cost");
    report.timing_note = note;
    if (o.strict_half)
        report.timing_note += ". precision=half variants are built strict: explicit 16-bit types, "
                              "computed at 16 bits";
    report.timing_trustworthy = run.timing_trustworthy();
    if (o.cost) {
        std::snprintf(note, sizeof note,
                      "instructions lavapipe executes per pixel for one %ux%u draw of the GLSL "
                      "path (valgrind callgrind, the draw alone; independent of machine load). "
                      "A/A: %.5f",
                      o.cost_size, o.cost_size, run.cost_aa);
        report.cost_note = note;
    }
    for (const GpuTarget& t : s.gpu_targets)
        report.cost_targets.push_back(t.name);
    if (!s.gpu_targets.empty())
        report.cost_note += std::string(report.cost_note.empty() ? "" : ". ") +
                            "Per AMD target: ACO's fragment instructions per pixel of the GLSL "
                            "path on RADV's null device (Mesa's AMD compiler, no GPU), each loop "
                            "body weighted by its trip count (static count where the driver "
                            "unrolled every loop); the target Pareto fronts use these";
}

// The note the report shows above the caustics passes.
std::string caustics_note(const RatioInterval& aa, const CompareSetup& s) {
    return fmt::format(
        "Each caustics variant renders over its own pass's map: the pass of its method and wave "
        "model drawn on the device for each view ({} m deep, window and sun as the view's). "
        "Below, in view {}: the texture (GLSL path) against the CPU photon reference of the same "
        "values ({} photons per texel); draw times interleaved, {} rounds x {} draws, the first "
        "(JIT) draw excluded, each round's median; A/A of the first pass {:.3f} [{:.3f}, {:.3f}].",
        kSceneCausticsDepth, s.views.front().first,
        kSceneCausticsReferencePhotons * kSceneCausticsReferencePhotons, s.spec.rounds,
        s.spec.draws, aa.ratio, aa.lo, aa.hi);
}

} // namespace

CompareOutcome compare_and_report(VulkanRunner& runner, const CompareSetup& setup) {
    CompareOutcome out;
    auto stop = [&out](std::string error) {
        out.error = std::move(error);
        out.status = RunStatus::Failed;
        return std::move(out);
    };
    CompareRequest request = compare_request(setup);
    // The caustics pass of a variant is the one its build ships: its material's, or for
    // variants named by flags a material of the preset alone.
    CompareCaustics caustics(runner, request.views,
                             setup.from_material ? setup.material : preset_material(setup.preset));
    request.textures_for = [&caustics](const VariantBuild& water, size_t view, std::string* error) {
        return caustics.textures_for(water, view, error);
    };
    CompareReport report;
    stream_into(request, setup, report);
    out.run = run_compare(runner, request);
    if (!out.run.ok()) {
        out.diagnostics = out.run.diagnostics;
        return stop(out.run.error);
    }
    std::string error;
    out.caustics = caustics.time(setup.spec.rounds, setup.spec.draws, &out.caustics_aa, &error);
    if (!error.empty()) return stop(error);
    if (setup.spec.cost && setup.lavapipe_cost)
        if (std::string e = add_costs(setup, out.run); !e.empty()) return stop(e);
    if (!setup.gpu_targets.empty()) {
        bool no_device = false;
        if (std::string e = add_gpu_costs(setup, request, out.run, &no_device); !e.empty()) {
            out = stop(e);
            if (no_device) out.status = RunStatus::NoDevice;
            return out;
        }
    }
    complete_report(report, out.run, setup);
    if (!out.caustics.empty()) {
        out.caustics_note = caustics_note(out.caustics_aa, setup);
        report.caustics_note = out.caustics_note;
        report.caustics_passes = caustics_pass_figures(out.caustics);
    }
    if (auto failure = write_compare_report(setup.spec.out, report)) {
        out.write_error = *failure;
        out.status = RunStatus::Failed;
    }
    return out;
}

} // namespace watergen
