// `watergen compare`: variants side by side against one reference (render/compare_run.h), with
// draw times (interleaved, A/A-checked) and the load-free cost (valgrind instruction counts).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <fmt/core.h>

#include "commands.h"
#include "watergen/eval/compare/compare_caustics.h"
#include "watergen/eval/compare/compare_run.h"
#include "watergen/eval/compare/pick.h"
#include "watergen/eval/compare/prune_measure.h"
#include "watergen/eval/report/compare_report.h"
#include "watergen/eval/scene/scene_views.h"
#include "watergen/plan/scene_pruning.h"

namespace watergen::cli {

namespace {

struct CompareOptions {
    std::vector<std::string> axis_lists; // per axis, "" or a comma list of choices
    std::vector<std::string> keys;       // --variant
    std::string preset, reference = "gold", out = "out/compare";
    std::string material, scene; // select a material's variants, or a scene's pruned set
    std::string views;           // comma list; "" = every view
    uint32_t size = 512, rounds = 40, draws = 3, cost_size = 64;
    bool cost = true, strict_half = false;
    RunnerSetup runner;
};

constexpr size_t kMaxVariants = 64;

std::vector<std::string> split_commas(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        out.push_back(item);
    return out;
}

// The variants the options name: every combination of the axis lists (other axes at their
// defaults), then the --variant keys. Prints the reason and returns nullopt on bad input.
std::optional<std::vector<Variant>> selected_variants(const CompareOptions& o) {
    std::vector<Variant> out;
    const auto& list = axes();
    bool any_list = false;
    std::vector<Variant> product = {default_variant()};
    for (size_t a = 0; a < list.size(); ++a) {
        if (o.axis_lists[a].empty()) continue;
        any_list = true;
        std::vector<Variant> next;
        for (const Variant& base : product)
            for (const std::string& choice : split_commas(o.axis_lists[a])) {
                Variant v = base;
                if (auto error = set_choice(v, list[a].name, choice)) {
                    std::fprintf(stderr, "watergen: error: --%s: %s\n", list[a].name.c_str(),
                                 error->c_str());
                    return std::nullopt;
                }
                next.push_back(v);
            }
        product = std::move(next);
        if (product.size() > kMaxVariants) break;
    }
    if (any_list) out = product;
    for (const std::string& key : o.keys) {
        std::string error;
        const auto v = parse_variant_key(key, &error);
        if (!v) {
            std::fprintf(stderr, "watergen: error: --variant '%s': %s\n", key.c_str(),
                         error.c_str());
            return std::nullopt;
        }
        out.push_back(*v);
    }
    if (out.empty()) {
        std::fprintf(stderr, "watergen: error: nothing to compare: give a comma list on an axis "
                             "flag (--fresnel schlick,exact) or --variant KEY\n");
        return std::nullopt;
    }
    if (out.size() > kMaxVariants) {
        std::fprintf(stderr, "watergen: error: %zu variants or more to compare; at most %zu\n",
                     out.size(), kMaxVariants);
        return std::nullopt;
    }
    return out;
}

// The choices where `v` differs from `base`, "fresnel=schlick extinction=linear", or "(same)".
std::string differences(const Variant& v, const Variant& base) {
    std::string out;
    const auto& list = axes();
    for (size_t a = 0; a < list.size(); ++a)
        if (v.choices[a] != base.choices[a])
            out += (out.empty() ? "" : " ") + list[a].name + "=" + v.choices[a];
    return out.empty() ? "(the reference)" : out;
}

void print_table(const CompareRun& run, const std::vector<std::string>& views) {
    std::printf("reference: %s%s\n", run.reference.key().c_str(),
                run.reference_on_cpu ? " (CPU, double)" : " (GPU)");
    std::printf("%-44s %-12s %24s %12s %8s", "variant (differs from the reference in)", "relation",
                "time ratio [95% CI]", "cost/pixel", "SPIR-V");
    for (const auto& v : views)
        std::printf(" %22s", (v + " max|dE p99").c_str());
    std::printf("\n");
    for (const CompareEntry& e : run.entries) {
        const std::string relation = e.relation.substr(0, e.relation.find(' '));
        char time[64];
        std::snprintf(time, sizeof time, "%.3f [%.3f, %.3f]", e.time.ratio, e.time.lo, e.time.hi);
        std::printf("%-44s %-12s %24s %12.1f %8zu", differences(e.variant, run.reference).c_str(),
                    relation.c_str(), time, e.cost_per_pixel, e.spirv_instructions);
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

// The caustics passes' lines, and the note the report shows above them.
std::string print_caustics(const std::vector<ComparedCausticsPass>& passes, const RatioInterval& aa,
                           const CompareRequest& request, const CompareOptions& o) {
    const std::string note = fmt::format(
        "Each caustics variant renders over its own pass's map: the pass of its method and wave "
        "model drawn on the device for each view ({} m deep, window and sun as the view's). "
        "Below, in view {}: the texture (GLSL path) against the CPU photon reference of the same "
        "values ({} photons per texel); draw times interleaved, {} rounds x {} draws, the first "
        "(JIT) draw excluded, each round's median; A/A of the first pass {:.3f} [{:.3f}, {:.3f}].",
        kSceneCausticsDepth, request.views.front().first,
        kSceneCausticsReferencePhotons * kSceneCausticsReferencePhotons, o.rounds, o.draws,
        aa.ratio, aa.lo, aa.hi);
    std::printf("caustics passes in view %s, against the CPU photon reference:\n",
                request.views.front().first.c_str());
    std::printf("  %-30s %6s %28s %9s %8s %10s\n", "pass", "texels", "draw ms median [min, max]",
                "max abs", "RMSE", "GLSL-HLSL");
    for (const ComparedCausticsPass& c : passes)
        std::printf("  %-30s %6u %8.3f [%8.3f, %8.3f] %9.4f %8.4f %10.3g\n", c.name.c_str(),
                    c.first.texels, c.median_ms, c.min_ms, c.max_ms, c.first.vs_reference.max_abs,
                    c.first.vs_reference.rmse, c.first.glsl_vs_hlsl);
    return note;
}

// The report of a run: images, maps, table and plots (compare_report.h).
CompareReport make_report(const CompareRun& run, const CompareRequest& request,
                          const CompareOptions& o) {
    CompareReport report;
    report.title = "watergen compare: " + std::to_string(run.entries.size()) + " variants";
    report.reference_key = run.reference.key() + (run.reference_on_cpu ? " (CPU, double)" : "");
    for (size_t v = 0; v < request.views.size(); ++v)
        report.views.push_back({request.views[v].first, run.reference_images[v]});
    const auto& list = axes();
    for (const CompareEntry& e : run.entries) {
        CompareVariant cv;
        cv.key = e.variant.key();
        for (size_t a = 0; a < list.size(); ++a)
            cv.choices[list[a].name] = e.variant.choices[a];
        cv.reference = e.variant.key() == run.reference.key();
        cv.relation = e.relation;
        cv.time_ratio = e.time.ratio;
        cv.time_ratio_lo = e.time.lo;
        cv.time_ratio_hi = e.time.hi;
        cv.cost = e.cost_per_pixel;
        cv.spirv_instructions = e.spirv_instructions;
        for (const ComparedView& view : e.views)
            cv.views.push_back({view.image, std::nullopt});
        report.variants.push_back(std::move(cv));
    }
    char note[400];
    std::snprintf(note, sizeof note,
                  "steady draw time on lavapipe (GLSL path, view %s, %ux%u), interleaved: %u "
                  "rounds x %u draws, the first (JIT) draw excluded; ratio = median over rounds, "
                  "95%% paired bootstrap interval. A/A (the reference against a second pipeline "
                  "of itself): %.3f [%.3f, %.3f]%s",
                  request.views.front().first.c_str(), request.views.front().second.width,
                  request.views.front().second.height, o.rounds, o.draws, run.aa.ratio, run.aa.lo,
                  run.aa.hi,
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
    return report;
}

// What is compared and how it is built: flags and keys (build_variant with the preset), or a
// material's variants (composed by the material), or a scene's pruned set of them (folded under
// the scene's facts, rendered in the synthetic scene made to obey them).
struct Selection {
    std::vector<Variant> variants;
    const Preset* preset = nullptr;
    std::vector<const Preset*> presets; // --preset a,b: each view is rendered under each
    Material material;
    std::optional<ScenePlan> plan;
    bool from_material = false;
};

bool select_from_material(const CompareOptions& o, Selection& sel, const Common& common) {
    if (std::any_of(o.axis_lists.begin(), o.axis_lists.end(),
                    [](const std::string& l) { return !l.empty(); }) ||
        !o.keys.empty()) {
        std::fprintf(stderr, "watergen: error: --material / --scene select the variants; give "
                             "them without axis lists or --variant\n");
        return false;
    }
    std::vector<SceneFacts> scenes;
    const std::vector<std::string> paths =
        o.scene.empty() ? std::vector<std::string>{} : std::vector<std::string>{o.scene};
    if (!load_material_and_scenes(o.material, paths, sel.material, scenes, common)) return false;
    sel.from_material = true;
    if (!scenes.empty()) {
        Diagnostics ds;
        sel.plan = plan_scene(sel.material, scenes.front(), ds);
        print_diagnostics(ds, common);
        if (!sel.plan) return false;
        sel.variants = sel.plan->variants;
    } else {
        enumerate(sel.material.space, [&](const Variant& v) { sel.variants.push_back(v); });
    }
    if (sel.variants.size() > kMaxVariants) {
        std::fprintf(stderr,
                     "watergen: error: %zu variants to compare; at most %zu (give a "
                     "--scene to compare its pruned set)\n",
                     sel.variants.size(), kMaxVariants);
        return false;
    }
    return true;
}

bool select(const CompareOptions& o, Selection& sel, const Common& common) {
    if (!o.material.empty() || !o.scene.empty()) return select_from_material(o, sel, common);
    const auto variants = selected_variants(o);
    if (!variants) return false;
    sel.variants = *variants;
    // Several presets are views of their own; the variants are built with the first (a preset
    // sets parameter values, which every view's scene uniforms set again).
    const std::vector<std::string> presets = split_commas(o.preset);
    for (const std::string& name : presets) {
        const Preset* p = nullptr;
        for (const Variant& v : sel.variants)
            if (!resolve_variant(v, name, &p)) return false;
        sel.presets.push_back(p);
    }
    if (sel.presets.empty()) sel.presets.push_back(nullptr);
    sel.preset = sel.presets.front();
    return true;
}

// Fills the variants' cost per pixel and the cost's A/A pair (the reference counted once more,
// on its own pipeline); false after printing the failure.
bool add_costs(const CompareOptions& o, const Selection& sel, const std::string& first_view,
               CompareRun& run) {
    std::vector<Variant> counted;
    for (const CompareEntry& e : run.entries)
        counted.push_back(e.variant);
    const std::string key = run.reference.key();
    counted.push_back(run.reference);
    if (std::none_of(run.entries.begin(), run.entries.end(),
                     [&](const CompareEntry& e) { return e.variant.key() == key; }))
        counted.push_back(run.reference);
    std::string error;
    const auto costs =
        sel.from_material
            ? count_material_costs(o.material, o.scene, counted, o.cost_size, &error)
            : count_draw_costs(counted, o.cost_size, sel.preset ? sel.preset->name : "",
                               first_view.substr(0, first_view.find('@')), &error, o.strict_half);
    if (!costs) {
        std::fprintf(stderr, "watergen: error: instruction count: %s\n", error.c_str());
        return false;
    }
    const double pixels = double(o.cost_size) * o.cost_size;
    for (CompareEntry& e : run.entries)
        if (auto it = costs->find(e.variant.key()); it != costs->end())
            e.cost_per_pixel = double(it->second) / pixels;
    if (costs->count(key) && costs->count(key + "#2") && costs->at(key) > 0) {
        run.reference_cost_per_pixel = double(costs->at(key)) / pixels;
        run.cost_aa = double(costs->at(key + "#2")) / double(costs->at(key));
    }
    return true;
}

// The views named by --views, or every view.
std::vector<const SceneView*> chosen_views(const CompareOptions& o) {
    std::vector<const SceneView*> out;
    if (o.views.empty())
        for (const SceneView& v : scene_views())
            out.push_back(&v);
    for (const std::string& name : split_commas(o.views))
        out.push_back(find_scene_view(name));
    return out;
}

int run_compare_command(const CompareOptions& o, const Common& common) {
    // The report replaces --out whole: only an empty directory or an earlier report may go.
    std::error_code ec;
    const std::filesystem::path out(o.out);
    if (std::filesystem::exists(out, ec) &&
        (!std::filesystem::is_directory(out, ec) ||
         (!std::filesystem::is_empty(out, ec) &&
          !std::filesystem::exists(out / kCompareReportHtml, ec)))) {
        std::fprintf(stderr,
                     "watergen: error: --out %s: exists and is not an earlier watergen compare "
                     "report (the report replaces the directory whole); give a new or empty "
                     "directory\n",
                     o.out.c_str());
        return kUsage;
    }
    Selection sel;
    if (!select(o, sel, common)) return kUsage;
    CompareRequest request;
    request.variants = sel.variants;
    request.preset = sel.preset;
    if (o.reference != "gold") {
        std::string error;
        request.reference = parse_variant_key(o.reference, &error);
        if (!request.reference) {
            std::fprintf(stderr, "watergen: error: --reference '%s': %s\n", o.reference.c_str(),
                         error.c_str());
            return kUsage;
        }
        const Preset* ignored = nullptr;
        if (!resolve_variant(*request.reference, sel.preset ? sel.preset->name : "", &ignored))
            return kUsage;
    }
    request.rounds = o.rounds;
    request.draws = o.draws;
    if (o.strict_half && sel.from_material) {
        std::fprintf(stderr, "watergen: error: --strict-half compares variants named by axis "
                             "flags or --variant; a material's variants are built as its build "
                             "ships them (relaxed-precision hints)\n");
        return kUsage;
    }
    if (o.strict_half)
        request.build = [&sel](const Variant& v) {
            EmitOptions strict;
            strict.strict_half = true;
            return build_variant(v, sel.preset, strict);
        };
    if (sel.from_material)
        request.build = [&sel](const Variant& v) {
            return sel.plan ? build_for_scene(sel.material, *sel.plan, v)
                            : build_shader(sel.material.compose(v));
        };
    for (const SceneView* view : chosen_views(o)) {
        if (!sel.from_material) {
            for (const Preset* p : sel.presets)
                request.views.emplace_back(sel.presets.size() > 1 ? view->name + "@" + p->name
                                                                  : view->name,
                                           preset_scene(o.size, o.size, p, view->name));
            continue;
        }
        if (const std::string why = sel.plan ? view_outside_scene(*view, sel.plan->scene) : "";
            !why.empty()) {
            if (!o.views.empty()) { // asked for by name: say so rather than drop it
                std::fprintf(stderr, "watergen: error: --views %s: %s\n", view->name.c_str(),
                             why.c_str());
                return kUsage;
            }
            std::printf("view %s left out: %s\n", view->name.c_str(), why.c_str());
            continue;
        }
        const SyntheticScene base = make_synthetic_scene(o.size, o.size, *view);
        request.views.emplace_back(view->name,
                                   sel.plan ? conform_scene(base, *sel.plan, sel.material) : base);
    }
    if (request.views.empty() && sel.plan) {
        std::fprintf(stderr, "watergen: error: --scene %s shows none of the views\n",
                     sel.plan->scene.name.c_str());
        return kUsage;
    }
    std::string cache;
    auto runner = create_runner(o.runner, &cache);
    if (!runner) return kNoDevice;
    if (o.strict_half && !runner->device_info().shader_float16) {
        std::fprintf(stderr, "watergen: error: %s has no shaderFloat16; strict half needs it\n",
                     runner->device_info().name.c_str());
        return kNoDevice;
    }
    CompareCaustics caustics(*runner, request.views);
    request.textures_for = [&caustics](const VariantBuild& water, size_t view, std::string* error) {
        return caustics.textures_for(water, view, error);
    };
    CompareRun run = run_compare(*runner, request);
    if (!bench_succeeded(run.diagnostics, run.error, common)) return kFailed;
    RatioInterval caustics_aa;
    std::string caustics_error;
    const auto passes = caustics.time(o.rounds, o.draws, &caustics_aa, &caustics_error);
    if (!caustics_error.empty()) {
        std::fprintf(stderr, "watergen: error: %s\n", caustics_error.c_str());
        return kFailed;
    }
    if (o.cost && !add_costs(o, sel, request.views.front().first, run)) return kFailed;
    std::vector<std::string> views;
    for (const auto& [name, scene] : request.views)
        views.push_back(name);
    print_table(run, views);
    CompareReport report = make_report(run, request, o);
    if (!passes.empty()) {
        report.caustics_note = print_caustics(passes, caustics_aa, request, o);
        report.caustics_passes = caustics_pass_figures(passes);
    }
    if (auto failure = write_compare_report(o.out, report)) {
        std::fprintf(stderr, "watergen: error: %s\n", failure->c_str());
        return kFailed;
    }
    std::printf("wrote %s/%s, %s, %s\n", o.out.c_str(), kCompareReportHtml, kCompareCsv,
                kCompareJson);
    return kOk;
}

} // namespace

Runner add_compare_command(CLI::App& app, const Common& common) {
    auto o = std::make_shared<CompareOptions>();
    const auto& list = axes();
    o->axis_lists.resize(list.size());
    for (size_t a = 0; a < list.size(); ++a)
        app.add_option("--" + list[a].name, o->axis_lists[a],
                       "choices of " + list[a].name + " to compare, comma-separated (default: " +
                           list[a].default_choice + " only)");
    app.add_option("--variant", o->keys, "a variant key to compare (repeatable)");
    app.add_option("--preset", o->preset,
                   "parameter preset, or several comma-separated: each view is rendered under "
                   "each (views named <view>@<preset>)");
    app.add_option("--material", o->material,
                   "compare the variants of this material file (with --scene: its pruned set)");
    app.add_option("--scene", o->scene,
                   "compare the variants this scene file reaches of the material (default: the "
                   "built-in material), built as the scene's build ships them");
    app.add_option("--reference", o->reference,
                   "gold (default): the gold of every axis that varies, on the CPU in double; or a "
                   "variant key, rendered on the GPU");
    app.add_option("--views", o->views,
                   "views to render, comma-separated (default: every view: " + scene_view_names() +
                       "); the first is the one timed")
        ->check([](const std::string& list) -> std::string {
            for (const std::string& name : split_commas(list))
                if (!find_scene_view(name))
                    return "'" + name + "' is not a view (" + scene_view_names() + ")";
            return "";
        });
    app.add_option("--size", o->size, "image width and height (default 512)")
        ->check(CLI::Range(16, 2048));
    app.add_option("--rounds", o->rounds,
                   "timing rounds, interleaved (default 40: at 15, the A/A interval came out wider "
                   "than +-3% in 3 of 5 runs on an idle 2-core machine)")
        ->check(CLI::Range(3, 1000));
    add_instrument_options(app, o->draws, o->cost_size, o->cost);
    app.add_flag("--strict-half", o->strict_half,
                 "build precision=half variants in explicit 16-bit types, so that lavapipe "
                 "computes them at 16 bits (with the default relaxed-precision hints it computes "
                 "them at 32, and half equals full)");
    app.add_option("--out", o->out, "output directory (default out/compare)");
    add_runner_options(app, o->runner);
    return [o, &common]() { return run_compare_command(*o, common); };
}

} // namespace watergen::cli
