#include "watergen/eval/compare/compare_setup.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "watergen/eval/report/compare_report.h"
#include "watergen/eval/scene/scene_conform.h"
#include "watergen/ir/core/text.h"
#include "watergen/plan/scene_file.h"

namespace watergen {

namespace {

bool refuse(CompareSetup& s, std::string error) {
    s.error = std::move(error);
    s.status = RunStatus::BadInput;
    return false;
}

// The report replaces --out whole: only an empty directory or an earlier report may go.
bool out_replaceable(CompareSetup& s) {
    std::error_code ec;
    const std::filesystem::path out(s.spec.out);
    if (std::filesystem::exists(out, ec) &&
        (!std::filesystem::is_directory(out, ec) ||
         (!std::filesystem::is_empty(out, ec) &&
          !std::filesystem::exists(out / kCompareReportHtml, ec))))
        return refuse(s, "--out " + s.spec.out +
                             ": exists and is not an earlier watergen compare report (the report "
                             "replaces the directory whole); give a new or empty directory");
    return true;
}

// The variants the flags name: every combination of the axis lists (other axes at their
// defaults), then the --variant keys.
bool select_variants(CompareSetup& s) {
    const auto& list = axes();
    bool any_list = false;
    std::vector<Variant> product = {default_variant()};
    // Past the cap the product is only counted (every choice still checked), so the refusal
    // names the real number without building a long list.
    size_t count = 1;
    for (size_t a = 0; a < list.size(); ++a) {
        if (s.spec.axis_lists[a].empty()) continue;
        any_list = true;
        const std::vector<std::string> choices = split(s.spec.axis_lists[a], ',');
        for (const std::string& choice : choices) {
            Variant v = default_variant();
            if (auto error = set_choice(v, list[a].name, choice))
                return refuse(s, "--" + list[a].name + ": " + *error);
        }
        count *= choices.size();
        if (count > kMaxComparedVariants) continue;
        std::vector<Variant> next;
        for (const Variant& base : product)
            for (const std::string& choice : choices) {
                Variant v = base;
                set_choice(v, list[a].name, choice);
                next.push_back(v);
            }
        product = std::move(next);
    }
    if (any_list && count <= kMaxComparedVariants) s.variants = product;
    if (!any_list) count = 0;
    for (const std::string& key : s.spec.keys) {
        std::string error;
        const auto v = parse_variant_key(key, &error);
        if (!v) return refuse(s, "--variant '" + key + "': " + error);
        s.variants.push_back(*v);
        ++count;
    }
    if (count == 0)
        return refuse(s, "nothing to compare: give a comma list on an axis flag (--fresnel "
                         "schlick,exact) or --variant KEY");
    if (count > kMaxComparedVariants)
        return refuse(
            s, fmt::format("{} variants to compare; at most {}", count, kMaxComparedVariants));
    return true;
}

bool select_from_material(CompareSetup& s) {
    const CompareSpec& o = s.spec;
    if (std::any_of(o.axis_lists.begin(), o.axis_lists.end(),
                    [](const std::string& l) { return !l.empty(); }) ||
        !o.keys.empty())
        return refuse(s, "--material / --scene select the variants; give them without axis "
                         "lists or --variant");
    std::vector<SceneFacts> scenes;
    const std::vector<std::string> paths =
        o.scene.empty() ? std::vector<std::string>{} : std::vector<std::string>{o.scene};
    Diagnostics loading; // shown only when loading fails, as every command shows them
    if (!load_material_and_scenes(o.material, paths, s.material, scenes, loading)) {
        s.diagnostics = std::move(loading);
        return refuse(s, "");
    }
    s.from_material = true;
    if (!scenes.empty()) {
        s.plan = plan_scene(s.material, scenes.front(), s.diagnostics);
        if (!s.plan) return refuse(s, "");
    }
    // Counted before they are listed: the whole space would be millions of Variants.
    const size_t count = s.plan ? s.plan->variants.size() : count_variants(s.material.space);
    if (count > kMaxComparedVariants)
        return refuse(s, fmt::format("{} variants to compare; at most {} (give a --scene to "
                                     "compare its pruned set)",
                                     count, kMaxComparedVariants));
    if (s.plan)
        s.variants.assign(s.plan->variants.begin(), s.plan->variants.end());
    else
        enumerate(s.material.space, [&](const Variant& v) { s.variants.push_back(v); });
    return true;
}

// The presets of --preset, checked against every variant; several are views of their own, the
// variants are built with the first (a preset sets parameter values, which every view's scene
// uniforms set again).
bool select_presets(CompareSetup& s, std::vector<const Preset*>& presets) {
    for (const std::string& name : split(s.spec.preset, ',')) {
        for (const Variant& v : s.variants)
            if (auto e = check_constraints(v)) return refuse(s, *e);
        presets.push_back(name.empty() ? nullptr : find_preset(name));
    }
    if (presets.empty()) presets.push_back(nullptr);
    s.preset = presets.front();
    return true;
}

bool select_reference(CompareSetup& s) {
    if (s.spec.reference == "gold") return true;
    std::string error;
    s.reference = parse_variant_key(s.spec.reference, &error);
    if (!s.reference) return refuse(s, "--reference '" + s.spec.reference + "': " + error);
    if (auto e = check_constraints(*s.reference)) return refuse(s, *e);
    return true;
}

// The views named by --views, or every view.
std::vector<const SceneView*> chosen_views(const CompareSpec& o) {
    std::vector<const SceneView*> out;
    if (o.views.empty())
        for (const SceneView& v : scene_views())
            out.push_back(&v);
    for (const std::string& name : split(o.views, ','))
        out.push_back(find_scene_view(name));
    return out;
}

bool add_views(CompareSetup& s, const std::vector<const Preset*>& presets) {
    const CompareSpec& o = s.spec;
    for (const SceneView* view : chosen_views(o)) {
        if (!s.from_material) {
            for (const Preset* p : presets)
                s.views.emplace_back(presets.size() > 1 ? view->name + "@" + p->name : view->name,
                                     preset_scene(o.size, o.size, p, view->name));
            continue;
        }
        if (const std::string why = s.plan ? view_outside_scene(*view, s.plan->scene) : "";
            !why.empty()) {
            // Asked for by name: say so rather than drop it.
            if (!o.views.empty()) return refuse(s, "--views " + view->name + ": " + why);
            s.notes.push_back("view " + view->name + " left out: " + why);
            continue;
        }
        const SyntheticScene base = make_synthetic_scene(o.size, o.size, *view);
        s.views.emplace_back(view->name, s.plan ? conform_scene(base, *s.plan, s.material) : base);
    }
    if (s.views.empty() && s.plan)
        return refuse(s, "--scene " + s.plan->scene.name + " shows none of the views");
    return true;
}

} // namespace

CompareSetup plan_compare(const CompareSpec& spec) {
    CompareSetup s;
    s.spec = spec;
    s.spec.axis_lists.resize(axes().size());
    std::string target_error;
    const auto targets = parse_gpu_targets(spec.targets, &target_error);
    if (!targets) {
        refuse(s, target_error);
        return s;
    }
    s.lavapipe_cost = spec.targets.empty() || has_lavapipe(*targets);
    s.gpu_targets = amd_targets(*targets);
    if (!out_replaceable(s)) return s;
    std::vector<const Preset*> presets;
    const bool selected = !spec.material.empty() || !spec.scene.empty()
                              ? select_from_material(s)
                              : select_variants(s) && select_presets(s, presets);
    if (!selected || !select_reference(s)) return s;
    if (const uint64_t pixels = uint64_t(s.variants.size()) * spec.size * spec.size;
        pixels > kMaxComparedPixels) {
        refuse(s, fmt::format("--size {}: {} variants at {}x{} are {} variant pixels per view; at "
                              "most {} (64 variants at 512x512, 16 at 1024x1024, 4 at "
                              "2048x2048): compare fewer variants or a smaller --size",
                              spec.size, s.variants.size(), spec.size, spec.size, pixels,
                              kMaxComparedPixels));
        return s;
    }
    if (spec.strict_half && s.from_material) {
        refuse(s, "--strict-half compares variants named by axis flags or --variant; a "
                  "material's variants are built as its build ships them (relaxed-precision "
                  "hints)");
        return s;
    }
    add_views(s, presets);
    return s;
}

} // namespace watergen
