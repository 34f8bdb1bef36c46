#include "watergen/plan/scene_pruning.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include <fmt/format.h>

#include "watergen/ir/core/text.h"
#include "watergen/water/scene_quantities.h"

#include "scene_bounds.h"

namespace watergen {

namespace {

bool has_source(const SceneFacts& s, const std::string& source) {
    return std::find(s.reflection_sources.begin(), s.reflection_sources.end(), source) !=
           s.reflection_sources.end();
}

// A choice's scene need (axis_registry.h), checked on variants where the axis holds the choice.
struct SceneRule {
    size_t axis; // position in axes()
    std::string choice;
    SceneNeed need;
};

// Every scene need of the registry, grouped by fact in SceneFact order, then axis order.
const std::vector<SceneRule>& scene_rules() {
    static const std::vector<SceneRule> rules = [] {
        std::vector<SceneRule> list;
        for (SceneFact fact :
             {SceneFact::Shoreline, SceneFact::ReflectionSource, SceneFact::SunAboveHorizon,
              SceneFact::BottomInView, SceneFact::BottomLit, SceneFact::Precision,
              SceneFact::SceneInput, SceneFact::CameraNear})
            for (size_t a = 0; a < axes().size(); ++a)
                for (const auto& c : axes()[a].choices)
                    for (const auto& need : c.scene_needs)
                        if (need.fact == fact) list.push_back({a, c.name, need});
        return list;
    }();
    return rules;
}

// Sunlight below this share of what enters the water lights nothing a float image can show:
// 2^-24 is binary32's resolution relative to the light at the surface (the water colour's
// surface-lit terms round away anything smaller).
constexpr double kSunlightSeen = 0x1p-24;

// Why no sunlight reaches the scene's shallowest bottom under v's extinction model, or "".
std::string bottom_unlit(const SceneFacts& s, const Variant& v, const ParameterBounds& bounds) {
    const AxisInfo* axis = find_axis("extinction");
    const ChoiceInfo* model = axis ? find_choice(*axis, v.choice("extinction")) : nullptr;
    if (!model || !model->sunlight_at_depth) return "";
    const double share = model->sunlight_at_depth(bounds, s.water_depth.min);
    if (share >= kSunlightSeen) return "";
    return fmt::format("water at least {:g} m deep lets at most {:.2g} of the sunlight reach the "
                       "bottom (extinction={}, parameters at their most transparent; below 2^-24)",
                       s.water_depth.min, share, model->name);
}

// Why no patch ever gets a factor above 1: an edge's factor is tess_scale / its distance from
// the eye (tessellated_mesh.h), at least the camera's height above the water level.
std::string camera_never_near(const SceneFacts& s, const ParameterBounds& bounds) {
    const double scale = bounds("tess_scale").second;
    if (s.camera_height.min < scale) return "";
    return fmt::format("the camera stays at least {:g} m above the water and tess_scale is at "
                       "most {:g} m, so every tessellation factor is 1",
                       s.camera_height.min, scale);
}

// Why the scene lacks what `need` asks for, or "" when it has it.
std::string unmet(const SceneFacts& s, const Variant& v, const SceneNeed& need,
                  const ParameterBounds* bounds) {
    std::string missing;
    switch (need.fact) {
    case SceneFact::Shoreline:
        if (!s.shoreline) missing = "no shoreline";
        break;
    case SceneFact::ReflectionSource:
        if (!has_source(s, need.value))
            missing =
                "no " + need.value + " among the scene's reflection sources (" +
                (s.reflection_sources.empty() ? std::string("none") : join(s.reflection_sources)) +
                ")";
        break;
    case SceneFact::SunAboveHorizon:
        if (!(s.sun_elevation.max > 0.0))
            missing = fmt::format("the sun never rises (elevation at most {:g} degrees)",
                                  s.sun_elevation.max);
        break;
    case SceneFact::BottomInView:
        if (!s.bottom_in_view) missing = "no bottom in view";
        break;
    case SceneFact::BottomLit:
        if (bounds) missing = bottom_unlit(s, v, *bounds);
        break;
    case SceneFact::Precision:
        if (s.precision != "any" && s.precision != need.value)
            missing = "the scene targets precision " + s.precision;
        break;
    case SceneFact::SceneInput:
        if (s.scene_input != "any" && s.scene_input != need.value)
            missing = "the engine gives the scene's position as " + s.scene_input;
        break;
    case SceneFact::CameraNear:
        if (bounds) missing = camera_never_near(s, *bounds);
        break;
    }
    if (missing.empty() || need.consequence.empty()) return missing;
    return missing + ", so " + need.consequence;
}

// Sorts the material's variants into those the scene reaches and those it skips, counting
// each skip's reason (grouped) for explain. A skipped variant finds its group by the parts of
// its exclusion, not by formatting its text: the full space skips millions, and the text was
// 11% of planning a scene.
void reach_variants(const Material& m, ScenePlan& plan) {
    auto same = [](const Exclusion& a, const Exclusion& b) {
        return a.reason == b.reason && a.axis == b.axis && a.choice == b.choice &&
               a.where == b.where;
    };
    std::vector<SkippedGroup>& groups = plan.skipped_groups;
    size_t last = 0; // the previous skipped variant's group: neighbours mostly share one
    const ParameterBounds bounds = parameter_bounds(m, plan.fixed);
    plan.variants = VariantList(m.space.choices);
    Variant v = default_variant();
    enumerate_indices(m.space, [&](const std::vector<size_t>& index) {
        for (size_t a = 0; a < index.size(); ++a)
            v.choices[a] = m.space.choices[a][index[a]];
        if (auto e = scene_excludes(plan.scene, v, &bounds)) {
            if (groups.empty() || !same(groups[last].exclusion, *e)) {
                last = static_cast<size_t>(
                    std::find_if(groups.begin(), groups.end(),
                                 [&](const SkippedGroup& g) { return same(g.exclusion, *e); }) -
                    groups.begin());
                if (last == groups.size()) groups.push_back({std::move(*e), 0});
            }
            ++groups[last].variants;
            ++plan.skipped;
        } else {
            plan.variants.add(index);
        }
    });
    plan.variants.sort_by_key();
    // In text order; groups of one text (parts that differ and print alike) counted as one.
    std::map<std::string, SkippedGroup> by_text;
    for (SkippedGroup& g : groups) {
        const auto [it, fresh] = by_text.try_emplace(g.text(), std::move(g)); // moved only if new
        if (!fresh) it->second.variants += g.variants;
    }
    groups.clear();
    for (auto& [text, g] : by_text)
        groups.push_back(std::move(g));
}

} // namespace

std::string SkippedGroup::text() const {
    return fmt::format("{}={}: {} [{}]", exclusion.axis, exclusion.choice, exclusion.reason,
                       exclusion.where);
}

ParameterBounds parameter_bounds(const Material& m,
                                 const std::map<std::string, std::vector<double>>& fixed) {
    return [&m, &fixed](const std::string& name) {
        auto it = fixed.find(name);
        if (it == fixed.end() || it->second.empty()) return m.range(name);
        const auto [lo, hi] = std::minmax_element(it->second.begin(), it->second.end());
        return std::pair<double, double>{*lo, *hi};
    };
}

std::optional<Exclusion> scene_excludes(const SceneFacts& scene, const Variant& v,
                                        const ParameterBounds* bounds) {
    for (const auto& r : scene_rules()) {
        if (v.choices[r.axis] != r.choice) continue;
        const std::string reason = unmet(scene, v, r.need, bounds);
        if (!reason.empty())
            return Exclusion{axes()[r.axis].name, r.choice, reason,
                             scene.where.of(std::string(scene_key(r.need.fact).key))};
    }
    return std::nullopt;
}

FoldFacts base_facts(const Material& m) {
    FoldFacts f;
    // The renderer's contract for the water pass inputs (synthetic_scene.h honours it).
    const size_t uv = f.add_fact("v_uv lies in [0, 1]", "");
    f.input_ranges["v_uv"] = {{make_interval(0.0, 1.0)}, uv};
    const size_t tex = f.add_fact(
        "scene textures are finite: colour in [0, 65504], positions within 100 km of the eye, "
        "window depth in [0, 1]",
        "");
    f.input_ranges["scene_color"] = {{make_interval(0.0, 65504.0)}, tex};
    f.input_ranges["scene_position"] = {{make_interval(-1e5, 1e5), make_interval(-1e5, 1e5),
                                         make_interval(-1e5, 1e5), make_interval(0.0, 1e6)},
                                        tex};
    f.input_ranges["scene_depth"] = {{make_interval(0.0, 1.0), make_interval(0.0, 1.0),
                                      make_interval(0.0, 1.0), make_interval(0.0, 1.0)},
                                     tex};
    for (const auto& [name, s] : m.parameters) {
        if (!s.min) continue;
        const size_t id = f.add_fact(
            fmt::format("{} in [{:g}, {:g}] (material {})", name, *s.min, *s.max, m.name), s.where);
        f.parameter_ranges[name] = {{make_interval(*s.min, *s.max)}, id};
    }
    return f;
}

std::optional<ScenePlan> plan_scene(const Material& m, const SceneFacts& scene, Diagnostics& ds) {
    auto fail = [&](Diagnostic d) -> std::optional<ScenePlan> {
        ds.push_back(std::move(d));
        return std::nullopt;
    };
    ScenePlan plan;
    plan.scene = scene;
    plan.facts = base_facts(m);
    const SceneWhere& w = scene.where;
    // In order: fixed values first (the camera and sun checks read them), then the ranges.
    for (auto step : {scene_bounds::fix_parameters, scene_bounds::bound_time,
                      scene_bounds::bound_camera, scene_bounds::bound_sun})
        if (auto error = step(m, plan)) return fail(std::move(*error));
    scene_bounds::bound_depth(plan);

    reach_variants(m, plan);
    if (plan.variants.empty()) {
        std::set<std::string> reasons;
        for (const auto& g : plan.skipped_groups)
            reasons.insert(g.exclusion.axis + "=" + g.exclusion.choice + ": " + g.exclusion.reason);
        std::string why;
        for (const auto& r : reasons)
            why += (why.empty() ? "" : "; ") + r;
        return fail(Diagnostic{Severity::Error,
                               w.fact.count("name") ? w.fact.at("name").file : scene.file,
                               w.fact.count("name") ? w.fact.at("name").position.line : 0,
                               w.fact.count("name") ? w.fact.at("name").position.column : 0, "",
                               "scene '" + scene.name + "' needs nothing: it reaches none of the " +
                                   std::to_string(plan.skipped) + " variants of material '" +
                                   m.name + "' (" + why + ")"});
    }
    // Targets its platforms need that the material emits.
    std::vector<std::string> wanted;
    for (Target t : all_targets()) {
        bool needed = false;
        for (const auto& p : scene.platforms)
            for (Target pt : platform_targets(p))
                needed = needed || pt == t;
        if (needed) wanted.push_back(to_string(t));
        if (needed && std::find(m.targets.begin(), m.targets.end(), t) != m.targets.end())
            plan.targets.push_back(t);
    }
    if (plan.targets.empty()) {
        std::vector<std::string> emitted;
        for (Target t : m.targets)
            emitted.push_back(to_string(t));
        return fail(w.error("platforms", "scene '" + scene.name + "' needs nothing material '" +
                                             m.name + "' emits: its platforms need " +
                                             join(wanted) + "; the material emits " +
                                             join(emitted)));
    }
    return plan;
}

} // namespace watergen
