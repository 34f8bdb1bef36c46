#include "watergen/eval/scene/synthetic_scene.h"

#include <cmath>

#include <glm/glm.hpp>

#include "scene_geometry.h"
#include "watergen/water/nodes/caustics.h"
#include "watergen/water/nodes/reflection.h"

namespace watergen {

namespace {

using glm::dvec3;
using scene_geometry::has_offset;
using scene_geometry::kPi;
using scene_geometry::placed;
using scene_geometry::sphere_entry;
using scene_geometry::sunlit;

constexpr double kFarDistance = kSceneSkyDistance;

struct Sphere {
    dvec3 centre;
    double radius;
    dvec3 albedo;
};

// Every view's: half buried in the seabed, its top 0.3 m under the surface.
const Sphere kSubmergedSphere{{1.5, -1.3, 3.0}, 1.0, {0.45, 0.22, 0.15}};

struct Hit {
    double t = kFarDistance;
    dvec3 normal{0.0, 1.0, 0.0};
    const Sphere* sphere = nullptr;
    bool ground = false;
};

Hit trace(const dvec3& o, const dvec3& d, const std::vector<Sphere>& spheres) {
    Hit hit;
    // Seabed plane y + 0.25 z - (2 - 3) = 0, i.e. n . p = -1 with n = (0, 1, 0.25).
    const dvec3 n{0.0, 1.0, 0.25};
    const double denom = glm::dot(n, d);
    if (denom < 0.0) {
        const double t = (-1.0 - glm::dot(n, o)) / denom;
        if (t > 0.0 && t < hit.t) {
            hit.t = t;
            hit.normal = glm::normalize(n);
            hit.ground = true;
        }
    }
    for (const Sphere& sphere : spheres) {
        const std::optional<double> t = sphere_entry(o, d, sphere.centre, sphere.radius);
        if (t && *t > 0.0 && *t < hit.t) {
            hit.t = *t;
            hit.normal = glm::normalize(o + d * *t - sphere.centre);
            hit.sphere = &sphere;
            hit.ground = false;
        }
    }
    return hit;
}

dvec3 sky(const dvec3& d) {
    const double up = std::max(d.y, 0.0);
    return glm::mix(dvec3{0.80, 0.85, 0.90}, dvec3{0.25, 0.45, 0.80}, std::sqrt(up));
}

dvec3 shade(const Hit& hit, const dvec3& p, const dvec3& to_sun) {
    dvec3 albedo;
    if (hit.sphere) {
        albedo = hit.sphere->albedo;
    } else {
        // Smooth ripples in the sand: two long-wavelength waves, no noise.
        const double ripple =
            0.5 + 0.25 * std::sin(2 * kPi * p.z / 3.0 + 0.7 * std::sin(2 * kPi * p.x / 9.0)) +
            0.25 * std::sin(2 * kPi * (p.x + 0.5 * p.z) / 7.0);
        albedo = glm::mix(dvec3{0.62, 0.55, 0.40}, dvec3{0.80, 0.72, 0.52}, ripple);
    }
    return sunlit(albedo, hit.normal, to_sun);
}

dvec3 to_dvec3(const double (&v)[3]) {
    return {v[0], v[1], v[2]};
}

std::vector<Sphere> view_spheres(const SceneView& view) {
    std::vector<Sphere> spheres = {kSubmergedSphere};
    if (const auto& s = view.standing_sphere)
        spheres.push_back({to_dvec3(s->centre), s->radius, to_dvec3(s->albedo)});
    return spheres;
}

} // namespace

std::map<std::string, TextureView>
texture_views(const std::map<std::string, TextureData>& textures) {
    std::map<std::string, TextureView> views;
    for (const auto& [name, t] : textures) {
        TextureView view{t.width, t.height, t.rgba.data()};
        view.layers = t.layers;
        views[name] = view;
    }
    return views;
}

EvalInputs SyntheticScene::eval_inputs() const {
    EvalInputs in;
    in.uniforms = uniforms;
    in.textures = texture_views(textures);
    in.filter = Filter::Linear;
    return in;
}

SceneCamera scene_camera(const SceneView& view, uint32_t width, uint32_t height) {
    const double yaw = view.yaw_degrees * kPi / 180.0, pitch = view.pitch_degrees * kPi / 180.0;
    const double half_fov = 0.5 * view.fov_y_degrees * kPi / 180.0;
    const dvec3 forward{std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                        std::cos(yaw) * std::cos(pitch)};
    // 0.0 - sin: +0 at yaw 0 (-sin would give -0, a different byte in the uniforms).
    const dvec3 right{std::cos(yaw), 0.0, 0.0 - std::sin(yaw)};
    const dvec3 up = glm::cross(forward, right);
    const dvec3 eye = placed(to_dvec3(view.eye), view.world_offset);
    return {{eye.x, eye.y, eye.z},       {forward.x, forward.y, forward.z},
            {right.x, right.y, right.z}, {up.x, up.y, up.z},
            std::tan(half_fov),          double(width) / height};
}

SceneCamera scene_camera(uint32_t width, uint32_t height) {
    return scene_camera(beach_view(), width, height);
}

SyntheticScene make_synthetic_scene(uint32_t width, uint32_t height) {
    return make_synthetic_scene(width, height, beach_view());
}

SyntheticScene make_synthetic_scene(uint32_t width, uint32_t height, const SceneView& view) {
    SyntheticScene s;
    s.width = width;
    s.height = height;
    s.view = view;
    TextureData color{width, height, 1, std::vector<float>(size_t(width) * height * 4)};
    TextureData position = color;

    const SceneCamera cam = scene_camera(view, width, height);
    // Traced and shaded around the origin, in double; positions stored relative to the eye, so
    // the same bytes at every offset, and the eye and the parameters' positions moved by it.
    const std::array<double, 3>& offset = view.world_offset;
    const dvec3 eye = to_dvec3(view.eye);
    const dvec3 forward = to_dvec3(cam.forward), right = to_dvec3(cam.right), up = to_dvec3(cam.up);
    const double tan_half = cam.tan_half_fov_y, aspect = cam.aspect;
    const dvec3 sun_travel = glm::normalize(to_dvec3(view.sun_travel));
    const std::vector<Sphere> spheres = view_spheres(view);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            // Pixel centre; row 0 is the top of the image.
            const double sx = (2.0 * (x + 0.5) / width - 1.0) * tan_half * aspect;
            const double sy = (1.0 - 2.0 * (y + 0.5) / height) * tan_half;
            const dvec3 d = glm::normalize(forward + right * sx + up * sy);
            const Hit hit = trace(eye, d, spheres);
            const dvec3 p = eye + d * hit.t;
            const dvec3 c = (hit.ground || hit.sphere) ? shade(hit, p, -sun_travel) : sky(d);
            const size_t i = (size_t(y) * width + x) * 4;
            for (int k = 0; k < 3; ++k) {
                color.rgba[i + k] = static_cast<float>(c[k]);
                position.rgba[i + k] = static_cast<float>(p[k] - eye[k]); // camera-relative
            }
            color.rgba[i + 3] = 1.0f;
            position.rgba[i + 3] = static_cast<float>(hit.t);
        }
    s.textures["scene_color"] = std::move(color);
    s.textures["scene_position"] = std::move(position);
    s.uniforms["eye_position"] = placed_scene_value("eye_position", {eye.x, eye.y, eye.z}, offset);
    const std::vector<double>& placed_eye = s.uniforms["eye_position"];
    s.position_eye = {placed_eye[0], placed_eye[1], placed_eye[2]};
    s.uniforms["water_level"] = placed_scene_value("water_level", {0.0}, offset);
    // The windows of the textures made over the scene (the Fourier horizon, the caustics map)
    // move with it; at offset 0 they are the parameters' defaults, left unset as of old.
    if (has_offset(offset))
        for (const Parameter& p : {fourier_map_origin(), caustics_window()})
            s.uniforms[p.name] = placed_scene_value(p.name, p.default_value, offset);
    s.uniforms["sun_direction"] = {sun_travel.x, sun_travel.y, sun_travel.z};
    s.uniforms["time"] = {0.0};
    add_foam_inputs(s);
    add_optics_inputs(s);
    add_wave_inputs(s);
    add_caustics_inputs(s);
    add_depth_inputs(s);
    return s;
}

std::vector<double> placed_scene_value(const std::string& name, std::vector<double> value,
                                       const std::array<double, 3>& world_offset) {
    // Which components of each position parameter are which world axes.
    static const std::map<std::string, std::vector<int>> kAxes = {
        {"eye_position", {0, 1, 2}},
        {"water_level", {1}},
        {"caustics_window", {0, 2}},    // x0, z0 (size stays)
        {"fourier_map_origin", {0, 2}}, // x, z
    };
    const auto it = kAxes.find(name);
    if (it == kAxes.end()) return value;
    for (size_t k = 0; k < it->second.size() && k < value.size(); ++k)
        value[k] = placed(value[k], world_offset[size_t(it->second[k])]);
    return value;
}

SyntheticScene preset_scene(uint32_t width, uint32_t height, const Preset* preset,
                            const std::string& view, const std::array<double, 3>& world_offset) {
    const SceneView* seen_from = find_scene_view(view);
    SceneView moved = seen_from ? *seen_from : beach_view();
    moved.world_offset = world_offset;
    SyntheticScene scene = make_synthetic_scene(width, height, moved);
    if (preset)
        for (const auto& [name, values] : preset->values)
            scene.uniforms[name] = placed_scene_value(name, values, world_offset);
    if (follow_scene_eye(scene)) add_depth_inputs(scene);
    return scene;
}

bool follow_scene_eye(SyntheticScene& scene) {
    const auto eye = scene.uniforms.find("eye_position");
    const auto position = scene.textures.find("scene_position");
    if (eye == scene.uniforms.end() || eye->second.size() != 3 || position == scene.textures.end())
        return false;
    const std::array<double, 3> to{eye->second[0], eye->second[1], eye->second[2]};
    if (to == scene.position_eye) return false;
    const std::array<double, 3>& from = scene.position_eye;
    std::vector<float>& rgba = position->second.rgba;
    for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
        if (!(rgba[i + 3] < kSceneSkyDistance)) continue; // the sky lies at infinity
        double r2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = (double(rgba[i + k]) + from[size_t(k)]) - to[size_t(k)];
            rgba[i + k] = static_cast<float>(d);
            r2 += d * d;
        }
        rgba[i + 3] = static_cast<float>(std::sqrt(r2));
    }
    scene.position_eye = to;
    return true;
}

} // namespace watergen
