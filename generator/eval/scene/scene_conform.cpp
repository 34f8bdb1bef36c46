#include "watergen/eval/scene/scene_conform.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "watergen/water/scene_quantities.h"

namespace watergen {

namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;

std::vector<double> uniform_value(const SyntheticScene& s, const Material& m,
                                  const std::string& name) {
    if (auto it = s.uniforms.find(name); it != s.uniforms.end()) return it->second;
    if (auto it = m.parameters.find(name); it != m.parameters.end() && it->second.value)
        return *it->second.value;
    if (auto it = m.declared.find(name); it != m.declared.end()) return it->second.default_value;
    return {};
}

} // namespace

std::string view_outside_scene(const SceneView& view, const SceneFacts& facts) {
    const FactRange& r = facts.camera_pitch;
    if (view.pitch_degrees >= r.min && view.pitch_degrees <= r.max) return "";
    return fmt::format("its camera pitch {:g} degrees is outside {}'s camera_pitch [{:g}, {:g}]",
                       view.pitch_degrees, facts.name, r.min, r.max);
}

SyntheticScene conform_scene(const SyntheticScene& base, const ScenePlan& plan, const Material& m,
                             std::string* notes) {
    SyntheticScene s = base;
    std::string log;
    const SceneFacts& f = plan.scene;
    for (const auto& [name, value] : plan.fixed)
        s.uniforms[name] = value;

    // The parameters the scene's facts bound, by their handles (scene_quantities.h).
    const std::string level_name(scene_quantity::water_level.parameter);
    const std::string eye_name(scene_quantity::eye_position.parameter);
    const std::string sun_name(scene_quantity::sun_direction.parameter);
    const std::vector<double> level_v = uniform_value(s, m, level_name);
    const double level = level_v.empty() ? 0.0 : level_v[0];
    std::vector<double> eye = uniform_value(s, m, eye_name);
    if (eye.size() == 3 && !plan.fixed.count(eye_name)) {
        const double y =
            std::clamp(eye[1], level + f.camera_height.min, level + f.camera_height.max);
        if (y != eye[1]) log += fmt::format("eye height {:g} -> {:g} m; ", eye[1], y);
        eye[1] = y;
        s.uniforms[eye_name] = eye;
    }
    std::vector<double> sun = uniform_value(s, m, sun_name);
    if (sun.size() == 3 && !plan.fixed.count(sun_name)) {
        const double len = std::sqrt(sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]);
        const double elevation = std::asin(std::clamp(-sun[1] / len, -1.0, 1.0)) / kDegrees;
        const double e = std::clamp(elevation, f.sun_elevation.min, f.sun_elevation.max);
        if (e != elevation) {
            // Same azimuth, new elevation; the sunlight travels downwards by day.
            const double horizontal = std::hypot(sun[0], sun[2]);
            const double c = std::cos(e * kDegrees);
            const double ax = horizontal > 0 ? sun[0] / horizontal : 1.0,
                         az = horizontal > 0 ? sun[2] / horizontal : 0.0;
            sun = {ax * c, -std::sin(e * kDegrees), az * c};
            log += fmt::format("sun elevation {:.3g} -> {:g} degrees; ", elevation, e);
        }
        s.uniforms[sun_name] = sun;
    }
    follow_scene_eye(s); // the texels relative to the conformed eye
    if (auto it = s.textures.find("scene_position"); it != s.textures.end() && eye.size() == 3) {
        size_t moved = 0;
        auto& rgba = it->second.rgba;
        const std::array<double, 3>& at = s.position_eye;
        for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
            const double px = at[0] + rgba[i], py = at[1] + rgba[i + 1], pz = at[2] + rgba[i + 2];
            if (!(py < level)) continue; // not under the water plane: not a water pixel
            // Waves move the surface around the plane: keep a margin from restrictive bounds
            // so that the depth under a displaced surface still obeys the fact.
            const double depth = level - py;
            const double margin = std::min(2.0, (f.water_depth.max - f.water_depth.min) / 4);
            const double d =
                std::clamp(depth, f.water_depth.min > 0 ? f.water_depth.min + margin : 0.0,
                           f.water_depth.max - margin);
            if (d == depth) continue; // depth does not depend on where the eye is
            // Slide along the ray from the eye through the point until the depth is d.
            const double t = (eye[1] - (level - d)) / (eye[1] - py);
            const double nx = eye[0] + (px - eye[0]) * t, ny = level - d,
                         nz = eye[2] + (pz - eye[2]) * t;
            rgba[i] = static_cast<float>(nx - at[0]);
            rgba[i + 1] = static_cast<float>(ny - at[1]);
            rgba[i + 2] = static_cast<float>(nz - at[2]);
            rgba[i + 3] = static_cast<float>(std::sqrt((nx - eye[0]) * (nx - eye[0]) +
                                                       (ny - eye[1]) * (ny - eye[1]) +
                                                       (nz - eye[2]) * (nz - eye[2])));
            ++moved;
        }
        if (moved)
            log += fmt::format("{} water texels moved into depth {:g}..{:g} m; ", moved,
                               f.water_depth.min, f.water_depth.max);
    }
    add_depth_inputs(s); // the moved texels' depth, and the conformed eye's matrix
    if (notes)
        *notes = log.empty() ? "the synthetic scene already obeys the facts"
                             : log.substr(0, log.size() - 2);
    return s;
}

} // namespace watergen
