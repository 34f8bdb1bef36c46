#include "watergen/plan/scene_pruning.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace watergen {

namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;

std::string join(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

bool has_source(const SceneFacts& s, const std::string& source) {
    return std::find(s.reflection_sources.begin(), s.reflection_sources.end(), source) != s.reflection_sources.end();
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
        for (SceneFact fact : {SceneFact::Shoreline, SceneFact::ReflectionSource,
                               SceneFact::SunAboveHorizon, SceneFact::Precision})
            for (size_t a = 0; a < axes().size(); ++a)
                for (const auto& c : axes()[a].choices)
                    for (const auto& need : c.scene_needs)
                        if (need.fact == fact) list.push_back({a, c.name, need});
        return list;
    }();
    return rules;
}

// The key of SceneWhere::fact a need reads.
std::string fact_key(SceneFact fact) {
    switch (fact) {
    case SceneFact::Shoreline:
        return "shoreline";
    case SceneFact::ReflectionSource:
        return "reflection_sources";
    case SceneFact::SunAboveHorizon:
        return "sun_elevation";
    case SceneFact::Precision:
        return "precision";
    }
    return "";
}

// Why the scene lacks what `need` asks for, or "" when it has it.
std::string unmet(const SceneFacts& s, const SceneNeed& need) {
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
    case SceneFact::Precision:
        if (s.precision != "any" && s.precision != need.value)
            missing = "the scene targets precision " + s.precision;
        break;
    }
    if (missing.empty() || need.consequence.empty()) return missing;
    return missing + ", so " + need.consequence;
}

std::string spell(const std::vector<double>& v) {
    if (v.size() == 1) return fmt::format("{:g}", v[0]);
    std::string s = "(";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt::format("{:g}", v[i]);
    return s + ")";
}

} // namespace

std::optional<Exclusion> scene_excludes(const SceneFacts& scene, const Variant& v) {
    for (const auto& r : scene_rules()) {
        if (v.choices[r.axis] != r.choice) continue;
        const std::string reason = unmet(scene, r.need);
        if (!reason.empty())
            return Exclusion{axes()[r.axis].name, r.choice, reason,
                             scene.where.of(fact_key(r.need.fact))};
    }
    return std::nullopt;
}

FoldFacts base_facts(const Material& m) {
    FoldFacts f;
    // The renderer's contract for the water pass inputs (synthetic_scene.h honours it).
    const size_t uv = f.add_fact("v_uv lies in [0, 1]", "");
    f.input_ranges["v_uv"] = {{make_interval(0.0, 1.0)}, uv};
    const size_t tex = f.add_fact("scene textures are finite: colour in [0, 65504], positions within 100 km", "");
    f.input_ranges["scene_color"] = {{make_interval(0.0, 65504.0)}, tex};
    f.input_ranges["scene_position"] = {{make_interval(-1e5, 1e5), make_interval(-1e5, 1e5), make_interval(-1e5, 1e5),
                                         make_interval(0.0, 1e6)},
                                        tex};
    for (const auto& [name, s] : m.parameters) {
        if (!s.min) continue;
        const size_t id = f.add_fact(fmt::format("{} in [{:g}, {:g}] (material {})", name, *s.min, *s.max, m.name), s.where);
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
    FoldFacts& f = plan.facts;
    const SceneWhere& w = scene.where;
    std::vector<std::string> read;
    for (const auto& [n, p] : m.declared) read.push_back(n);

    // Parameters the scene fixes by name.
    for (const auto& [name, value] : scene.fixed) {
        const std::string key = "fixed/" + name;
        auto it = m.declared.find(name);
        if (it == m.declared.end())
            return fail(w.error(key, "unknown parameter '" + name + "'; the nodes of material '" + m.name + "' read " + join(read)));
        const size_t n = static_cast<size_t>(component_count(it->second.type));
        if (value.size() != n)
            return fail(w.error(key, fmt::format("parameter '{}' is a {}: expected {} number{}, got {}", name,
                                                 type_name(it->second.type), n, n == 1 ? "" : "s", value.size())));
        const auto [lo, hi] = m.range(name);
        for (double x : value)
            if (x < lo || x > hi)
                return fail(w.error(key, fmt::format("{} = {:g} is out of range; expected a value in [{:g}, {:g}] {}", name, x,
                                                     lo, hi, it->second.unit)));
        plan.fixed[name] = value;
        f.fixed[name] = {value, f.add_fact(name + " = " + spell(value) + " (scene " + scene.name + ")", w.of(key))};
    }
    // Static waves: time stands still.
    if (m.declared.count("time")) {
        if (!scene.waves_animated && !scene.fixed.count("time")) {
            plan.fixed["time"] = {0.0};
            f.fixed["time"] = {{0.0}, f.add_fact("waves are static: time = 0", w.of("waves"))};
        }
        if (scene.waves_animated && scene.fixed.count("time"))
            return fail(w.error("fixed/time", "time is fixed but the scene's waves are animated; expected \"waves\": \"static\""));
    }
    // Camera height above the water level bounds eye_position.y.
    if (auto eye = m.declared.find("eye_position"); eye != m.declared.end() && eye->second.type == Type::Vec3) {
        auto [lvl_lo, lvl_hi] = m.range("water_level");
        if (auto it = plan.fixed.find("water_level"); it != plan.fixed.end()) lvl_lo = lvl_hi = it->second[0];
        const auto [elo, ehi] = m.range("eye_position");
        const Interval xz = make_interval(elo, ehi);
        const double ylo = std::max(elo, lvl_lo + scene.camera_height.min), yhi = std::min(ehi, lvl_hi + scene.camera_height.max);
        if (ylo > yhi)
            return fail(w.error("camera_height", "no camera position within eye_position's range satisfies the camera height"));
        if (!plan.fixed.count("eye_position"))
            f.parameter_ranges["eye_position"] = {
                {xz, make_interval(ylo, yhi), xz},
                f.add_fact(fmt::format("camera {:g}..{:g} m above the water", scene.camera_height.min, scene.camera_height.max),
                           w.of("camera_height"))};
    }
    // Sun elevation bounds the y of the direction the sunlight travels (downwards by day).
    if (auto sun = m.declared.find("sun_direction"); sun != m.declared.end() && sun->second.type == Type::Vec3) {
        const double ylo = -std::sin(scene.sun_elevation.max * kDegrees), yhi = -std::sin(scene.sun_elevation.min * kDegrees);
        if (auto it = plan.fixed.find("sun_direction"); it != plan.fixed.end()) {
            const auto& d = it->second;
            const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const double elevation = len > 0 ? std::asin(std::clamp(-d[1] / len, -1.0, 1.0)) / kDegrees : 0.0;
            if (elevation < scene.sun_elevation.min - 1e-9 || elevation > scene.sun_elevation.max + 1e-9)
                return fail(w.error("fixed/sun_direction",
                                    fmt::format("the fixed sun direction has elevation {:.3g} degrees; expected one within "
                                                "sun_elevation [{:g}, {:g}]",
                                                elevation, scene.sun_elevation.min, scene.sun_elevation.max)));
        } else {
            f.parameter_ranges["sun_direction"] = {
                {make_interval(-1.0, 1.0), make_interval(ylo, yhi), make_interval(-1.0, 1.0)},
                f.add_fact(fmt::format("sun elevation {:g}..{:g} degrees", scene.sun_elevation.min, scene.sun_elevation.max),
                           w.of("sun_elevation"))};
        }
    }
    // Water depth: a fact about water pixels, attached to the node the waves axis names.
    f.named_ranges["water_depth"] = {
        {make_interval(scene.water_depth.min, scene.water_depth.max)},
        f.add_fact(fmt::format("water depth {:g}..{:g} m", scene.water_depth.min, scene.water_depth.max), w.of("water_depth"))};

    // Variants the scene reaches.
    std::map<std::string, size_t> reasons;
    enumerate(m.space, [&](const Variant& v) {
        if (auto e = scene_excludes(scene, v)) {
            ++plan.skipped;
            ++reasons[e->axis + "=" + e->choice + ": " + e->reason];
        } else {
            plan.variants.push_back(v);
        }
    });
    std::sort(plan.variants.begin(), plan.variants.end(),
              [](const Variant& a, const Variant& b) { return a.key() < b.key(); });
    if (plan.variants.empty()) {
        std::string why;
        for (const auto& [r, n] : reasons) why += (why.empty() ? "" : "; ") + r;
        return fail(Diagnostic{Severity::Error, w.fact.count("name") ? w.fact.at("name").file : scene.file,
                               w.fact.count("name") ? w.fact.at("name").position.line : 0,
                               w.fact.count("name") ? w.fact.at("name").position.column : 0, "",
                               "scene '" + scene.name + "' needs nothing: it reaches none of the " +
                                   std::to_string(plan.skipped) + " variants of material '" + m.name + "' (" + why + ")"});
    }
    // Targets its platforms need that the material emits.
    std::vector<std::string> wanted;
    for (Target t : all_targets()) {
        bool needed = false;
        for (const auto& p : scene.platforms)
            for (Target pt : platform_targets(p)) needed = needed || pt == t;
        if (needed) wanted.push_back(to_string(t));
        if (needed && std::find(m.targets.begin(), m.targets.end(), t) != m.targets.end()) plan.targets.push_back(t);
    }
    if (plan.targets.empty()) {
        std::vector<std::string> emitted;
        for (Target t : m.targets) emitted.push_back(to_string(t));
        return fail(w.error("platforms", "scene '" + scene.name + "' needs nothing material '" + m.name + "' emits: its platforms need " +
                                             join(wanted) + "; the material emits " + join(emitted)));
    }
    return plan;
}

} // namespace watergen
