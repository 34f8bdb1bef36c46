#include "watergen/plan/scene_pruning.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include <fmt/format.h>

#include "watergen/ir/text.h"
#include "watergen/water/scene_quantities.h"

namespace watergen {

namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;

// A scene fact that rules out choices of one axis. `rules_out` returns the reason, or "" when
// the scene can use the choice.
struct SceneRule {
    std::string axis;
    std::string fact; // key of SceneWhere::fact
    std::function<std::string(const SceneFacts&, const std::string& choice)> rules_out;
};

bool has_source(const SceneFacts& s, const std::string& source) {
    return std::find(s.reflection_sources.begin(), s.reflection_sources.end(), source) != s.reflection_sources.end();
}

const std::vector<SceneRule>& scene_rules() {
    static const std::vector<SceneRule> rules = {
        {"foam", "shoreline",
         [](const SceneFacts& s, const std::string& c) -> std::string {
             if (s.shoreline || (c != "shore" && c != "both")) return "";
             return "no shoreline, so shore foam never shows";
         }},
        {"reflection", "reflection_sources",
         [](const SceneFacts& s, const std::string& c) -> std::string {
             const std::string need = c == "sky_cubemap" ? "cubemap" : c == "planar_projective" ? "planar"
                                      : c == "fourier_horizon" ? "horizon_map" : "";
             if (need.empty() || has_source(s, need)) return "";
             return "no " + need + " among the scene's reflection sources (" +
                    (s.reflection_sources.empty() ? std::string("none") : join(s.reflection_sources)) + ")";
         }},
        {"specular", "sun_elevation",
         [](const SceneFacts& s, const std::string& c) -> std::string {
             if (c == "none" || s.sun_elevation.max > 0.0) return "";
             return fmt::format("the sun never rises (elevation at most {:g} degrees), so there is no sun highlight",
                                s.sun_elevation.max);
         }},
        {"precision", "precision",
         [](const SceneFacts& s, const std::string& c) -> std::string {
             if (s.precision == "any" || s.precision == c) return "";
             return "the scene targets precision " + s.precision;
         }},
    };
    return rules;
}

std::string spell(const std::vector<double>& v) {
    if (v.size() == 1) return fmt::format("{:g}", v[0]);
    std::string s = "(";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt::format("{:g}", v[i]);
    return s + ")";
}

// Sorts the material's variants into those the scene reaches and those it skips, keeping
// each skip's reason (grouped) for explain.
void reach_variants(const Material& m, ScenePlan& plan) {
    std::map<std::string, uint32_t> group_of;
    uint32_t ordinal = 0;
    enumerate(m.space, [&](const Variant& v) {
        if (auto e = scene_excludes(plan.scene, v)) {
            SkippedGroup group{std::move(*e), 0};
            auto [it, fresh] = group_of.emplace(group.text(), static_cast<uint32_t>(plan.skipped_groups.size()));
            if (fresh) plan.skipped_groups.push_back(std::move(group));
            ++plan.skipped_groups[it->second].variants;
            plan.skipped_variants.push_back({ordinal, it->second});
            ++plan.skipped;
        } else {
            plan.variants.push_back(v);
        }
        ++ordinal;
    });
    std::sort(plan.variants.begin(), plan.variants.end(),
              [](const Variant& a, const Variant& b) { return a.key() < b.key(); });
    // Groups in text order; the variants' group indices follow them.
    std::vector<uint32_t> renumber(plan.skipped_groups.size());
    std::vector<SkippedGroup> sorted;
    for (const auto& [text, index] : group_of) {
        renumber[index] = static_cast<uint32_t>(sorted.size());
        sorted.push_back(std::move(plan.skipped_groups[index]));
    }
    plan.skipped_groups = std::move(sorted);
    for (auto& s : plan.skipped_variants) s.group = renumber[s.group];
}

} // namespace

std::string SkippedGroup::text() const {
    return fmt::format("{}={}: {} [{}]", exclusion.axis, exclusion.choice, exclusion.reason, exclusion.where);
}

std::optional<Exclusion> scene_excludes(const SceneFacts& scene, const Variant& v) {
    for (const auto& r : scene_rules()) {
        const std::string& choice = v.choice(r.axis);
        const std::string reason = r.rules_out(scene, choice);
        if (!reason.empty()) return Exclusion{r.axis, choice, reason, scene.where.of(r.fact)};
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
    // Scene facts about parameters go through their handles (scene_quantities.h): the fold
    // applies them to whatever uniform the handle is bound to.
    const std::string time = std::string(scene_quantity::time.parameter);
    const std::string eye_position = std::string(scene_quantity::eye_position.parameter);
    const std::string water_level = std::string(scene_quantity::water_level.parameter);
    const std::string sun_direction = std::string(scene_quantity::sun_direction.parameter);
    // Static waves: time stands still.
    if (m.declared.count(time)) {
        if (!scene.waves_animated && !scene.fixed.count(time)) {
            plan.fixed[time] = {0.0};
            f.fixed_quantities[scene_quantity::time] = {{0.0}, f.add_fact("waves are static: time = 0", w.of("waves"))};
        }
        if (scene.waves_animated && scene.fixed.count(time))
            return fail(w.error("fixed/time", "time is fixed but the scene's waves are animated; expected \"waves\": \"static\""));
    }
    // Camera height above the water level bounds eye_position.y.
    if (auto eye = m.declared.find(eye_position); eye != m.declared.end() && eye->second.type == scene_quantity::eye_position.type) {
        auto [lvl_lo, lvl_hi] = m.range(water_level);
        if (auto it = plan.fixed.find(water_level); it != plan.fixed.end()) lvl_lo = lvl_hi = it->second[0];
        const auto [elo, ehi] = m.range(eye_position);
        const Interval xz = make_interval(elo, ehi);
        const double ylo = std::max(elo, lvl_lo + scene.camera_height.min), yhi = std::min(ehi, lvl_hi + scene.camera_height.max);
        if (ylo > yhi)
            return fail(w.error("camera_height", "no camera position within eye_position's range satisfies the camera height"));
        if (!plan.fixed.count(eye_position))
            f.quantity_ranges[scene_quantity::eye_position] = {
                {xz, make_interval(ylo, yhi), xz},
                f.add_fact(fmt::format("camera {:g}..{:g} m above the water", scene.camera_height.min, scene.camera_height.max),
                           w.of("camera_height"))};
    }
    // Sun elevation bounds the y of the direction the sunlight travels (downwards by day).
    if (auto sun = m.declared.find(sun_direction); sun != m.declared.end() && sun->second.type == scene_quantity::sun_direction.type) {
        const double ylo = -std::sin(scene.sun_elevation.max * kDegrees), yhi = -std::sin(scene.sun_elevation.min * kDegrees);
        if (auto it = plan.fixed.find(sun_direction); it != plan.fixed.end()) {
            const auto& d = it->second;
            const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const double elevation = len > 0 ? std::asin(std::clamp(-d[1] / len, -1.0, 1.0)) / kDegrees : 0.0;
            if (elevation < scene.sun_elevation.min - 1e-9 || elevation > scene.sun_elevation.max + 1e-9)
                return fail(w.error("fixed/sun_direction",
                                    fmt::format("the fixed sun direction has elevation {:.3g} degrees; expected one within "
                                                "sun_elevation [{:g}, {:g}]",
                                                elevation, scene.sun_elevation.min, scene.sun_elevation.max)));
        } else {
            f.quantity_ranges[scene_quantity::sun_direction] = {
                {make_interval(-1.0, 1.0), make_interval(ylo, yhi), make_interval(-1.0, 1.0)},
                f.add_fact(fmt::format("sun elevation {:g}..{:g} degrees", scene.sun_elevation.min, scene.sun_elevation.max),
                           w.of("sun_elevation"))};
        }
    }
    // Water depth: a fact about water pixels, attached to the node the water column binds.
    f.quantity_ranges[scene_quantity::water_depth] = {
        {make_interval(scene.water_depth.min, scene.water_depth.max)},
        f.add_fact(fmt::format("water depth {:g}..{:g} m", scene.water_depth.min, scene.water_depth.max), w.of("water_depth"))};

    reach_variants(m, plan);
    if (plan.variants.empty()) {
        std::set<std::string> reasons;
        for (const auto& g : plan.skipped_groups) reasons.insert(g.exclusion.axis + "=" + g.exclusion.choice + ": " + g.exclusion.reason);
        std::string why;
        for (const auto& r : reasons) why += (why.empty() ? "" : "; ") + r;
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
