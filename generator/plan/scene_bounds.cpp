#include "scene_bounds.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "watergen/ir/core/text.h"
#include "watergen/water/scene_quantities.h"

namespace watergen::scene_bounds {

namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;

std::string parameter_of(const Quantity& q) {
    return std::string(q.parameter);
}

// The range of the water level: fixed by the scene, else the material's.
std::pair<double, double> water_level_range(const Material& m, const ScenePlan& plan) {
    const std::string level = parameter_of(scene_quantity::water_level);
    if (auto it = plan.fixed.find(level); it != plan.fixed.end())
        return {it->second[0], it->second[0]};
    return m.range(level);
}

} // namespace

std::optional<Diagnostic> fix_parameters(const Material& m, ScenePlan& plan) {
    const SceneFacts& scene = plan.scene;
    const SceneWhere& w = scene.where;
    for (const auto& [name, value] : scene.fixed) {
        const std::string key = "fixed/" + name;
        auto it = m.declared.find(name);
        if (it == m.declared.end()) {
            std::vector<std::string> read;
            for (const auto& [n, p] : m.declared)
                read.push_back(n);
            return w.error(key, "unknown parameter '" + name + "'; the nodes of material '" +
                                    m.name + "' read " + join(read));
        }
        const size_t n = value_count(it->second); // every element of an array
        if (value.size() != n)
            return w.error(key, fmt::format("parameter '{}' is a {}: expected {} number{}, got {}",
                                            name, type_name(it->second.type), n, n == 1 ? "" : "s",
                                            value.size()));
        const auto [lo, hi] = m.range(name);
        for (double x : value)
            if (!(x >= lo && x <= hi))
                return w.error(
                    key, fmt::format("{} = {} is out of range; expected a value in [{}, {}] {}",
                                     name, spell_number(x), spell_number(lo), spell_number(hi),
                                     it->second.unit));
        plan.fixed[name] = value;
        plan.facts.fixed[name] = {value, plan.facts.add_fact(name + " = " + spell_values(value) +
                                                                 " (scene " + scene.name + ")",
                                                             w.of(key))};
    }
    return std::nullopt;
}

std::optional<Diagnostic> bound_time(const Material& m, ScenePlan& plan) {
    const SceneFacts& scene = plan.scene;
    const std::string time = parameter_of(scene_quantity::time);
    if (!m.declared.count(time)) return std::nullopt;
    if (scene.waves_animated && scene.fixed.count(time))
        return scene.where.error(
            "fixed/time",
            "time is fixed but the scene's waves are animated; expected \"waves\": \"static\"");
    if (!scene.waves_animated && !scene.fixed.count(time)) {
        plan.fixed[time] = {0.0};
        plan.facts.fixed_quantities[scene_quantity::time] = {
            {0.0}, plan.facts.add_fact("waves are static: time = 0", scene.where.of("waves"))};
    }
    return std::nullopt;
}

// Camera height above the water level bounds eye_position.y; a fixed eye must obey it too.
std::optional<Diagnostic> bound_camera(const Material& m, ScenePlan& plan) {
    const SceneFacts& scene = plan.scene;
    const SceneWhere& w = scene.where;
    const std::string eye_position = parameter_of(scene_quantity::eye_position);
    auto eye = m.declared.find(eye_position);
    if (eye == m.declared.end() || eye->second.type != scene_quantity::eye_position.type)
        return std::nullopt;
    const auto [lvl_lo, lvl_hi] = water_level_range(m, plan);
    const double hmin = scene.camera_height.min, hmax = scene.camera_height.max;
    if (auto it = plan.fixed.find(eye_position); it != plan.fixed.end()) {
        // Over the whole range of the water level, the fixed eye must stay within the heights.
        const double y = it->second[1];
        if (y - lvl_hi < hmin || y - lvl_lo > hmax)
            return w.error("fixed/" + eye_position,
                           fmt::format("the fixed eye position is {} m above the water (eye y {}, "
                                       "water level {}..{} m); "
                                       "expected a height within camera_height [{}, {}] m",
                                       lvl_lo == lvl_hi ? spell_number(y - lvl_lo)
                                                        : spell_number(y - lvl_hi) + ".." +
                                                              spell_number(y - lvl_lo),
                                       spell_number(y), spell_number(lvl_lo), spell_number(lvl_hi),
                                       spell_number(hmin), spell_number(hmax)));
        return std::nullopt;
    }
    const auto [elo, ehi] = m.range(eye_position);
    const Interval xz = make_interval(elo, ehi);
    const double ylo = std::max(elo, lvl_lo + hmin), yhi = std::min(ehi, lvl_hi + hmax);
    if (ylo > yhi)
        return w.error(
            "camera_height",
            "no camera position within eye_position's range satisfies the camera height");
    plan.facts.quantity_ranges[scene_quantity::eye_position] = {
        {xz, make_interval(ylo, yhi), xz},
        plan.facts.add_fact(fmt::format("camera {:g}..{:g} m above the water", hmin, hmax),
                            w.of("camera_height"))};
    return std::nullopt;
}

// Sun elevation bounds the y of the direction the sunlight travels (downwards by day); a fixed
// direction must be a direction (finite, not zero) within the elevation range.
std::optional<Diagnostic> bound_sun(const Material& m, ScenePlan& plan) {
    const SceneFacts& scene = plan.scene;
    const SceneWhere& w = scene.where;
    const std::string sun_direction = parameter_of(scene_quantity::sun_direction);
    auto sun = m.declared.find(sun_direction);
    if (sun == m.declared.end() || sun->second.type != scene_quantity::sun_direction.type)
        return std::nullopt;
    const double emin = scene.sun_elevation.min, emax = scene.sun_elevation.max;
    if (auto it = plan.fixed.find(sun_direction); it != plan.fixed.end()) {
        const auto& d = it->second;
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(len >= 1e-6) || !std::isfinite(len))
            return w.error(
                "fixed/" + sun_direction,
                fmt::format(
                    "the fixed sun direction ({}, {}, {}) has length {}; expected a direction "
                    "(a zero vector would fold every sun term away)",
                    spell_number(d[0]), spell_number(d[1]), spell_number(d[2]), spell_number(len)));
        const double elevation = std::asin(std::clamp(-d[1] / len, -1.0, 1.0)) / kDegrees;
        if (elevation < emin - 1e-9 || elevation > emax + 1e-9)
            return w.error(
                "fixed/" + sun_direction,
                fmt::format("the fixed sun direction has elevation {} degrees; expected one within "
                            "sun_elevation [{}, {}]",
                            spell_number(elevation), spell_number(emin), spell_number(emax)));
        return std::nullopt;
    }
    const double ylo = -std::sin(emax * kDegrees), yhi = -std::sin(emin * kDegrees);
    plan.facts.quantity_ranges[scene_quantity::sun_direction] = {
        {make_interval(-1.0, 1.0), make_interval(ylo, yhi), make_interval(-1.0, 1.0)},
        plan.facts.add_fact(fmt::format("sun elevation {:g}..{:g} degrees", emin, emax),
                            w.of("sun_elevation"))};
    return std::nullopt;
}

// Water depth: a fact about water pixels, attached to the node the water column binds.
void bound_depth(ScenePlan& plan) {
    const SceneFacts& scene = plan.scene;
    plan.facts.quantity_ranges[scene_quantity::water_depth] = {
        {make_interval(scene.water_depth.min, scene.water_depth.max)},
        plan.facts.add_fact(
            fmt::format("water depth {:g}..{:g} m", scene.water_depth.min, scene.water_depth.max),
            scene.where.of("water_depth"))};
}

} // namespace watergen::scene_bounds
