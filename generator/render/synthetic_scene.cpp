#include "watergen/render/synthetic_scene.h"

#include <cmath>

#include <glm/glm.hpp>

namespace watergen {

namespace {

using glm::dvec3;

constexpr double kPi = 3.14159265358979323846;
const dvec3 kEye{0.0, 5.0, -7.0};
const dvec3 kSphereCentre{1.5, -1.3, 3.0};
constexpr double kSphereRadius = 1.0;
constexpr double kFarDistance = 1000.0;
// Direction the sunlight travels (000's convention: -L points at the sun).
const dvec3 kSunTravel = glm::normalize(dvec3{-0.35, -0.75, 0.55});

struct Hit {
    double t = kFarDistance;
    dvec3 normal{0.0, 1.0, 0.0};
    bool sphere = false, ground = false;
};

Hit trace(const dvec3& o, const dvec3& d) {
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
    const dvec3 oc = o - kSphereCentre;
    const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - kSphereRadius * kSphereRadius;
    const double disc = b * b - c;
    if (disc > 0.0) {
        const double t = -b - std::sqrt(disc);
        if (t > 0.0 && t < hit.t) {
            hit.t = t;
            hit.normal = glm::normalize(o + d * t - kSphereCentre);
            hit.sphere = true;
            hit.ground = false;
        }
    }
    return hit;
}

dvec3 sky(const dvec3& d) {
    const double up = std::max(d.y, 0.0);
    return glm::mix(dvec3{0.80, 0.85, 0.90}, dvec3{0.25, 0.45, 0.80}, std::sqrt(up));
}

dvec3 shade(const Hit& hit, const dvec3& p) {
    dvec3 albedo;
    if (hit.sphere) {
        albedo = {0.45, 0.22, 0.15};
    } else {
        // Smooth ripples in the sand: two long-wavelength waves, no noise.
        const double ripple =
            0.5 + 0.25 * std::sin(2 * kPi * p.z / 3.0 + 0.7 * std::sin(2 * kPi * p.x / 9.0)) +
            0.25 * std::sin(2 * kPi * (p.x + 0.5 * p.z) / 7.0);
        albedo = glm::mix(dvec3{0.62, 0.55, 0.40}, dvec3{0.80, 0.72, 0.52}, ripple);
    }
    const double lambert = std::max(glm::dot(hit.normal, -kSunTravel), 0.0);
    return albedo * (0.25 + 0.9 * lambert);
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

SceneCamera scene_camera(uint32_t width, uint32_t height) {
    const double pitch = -28.0 * kPi / 180.0, half_fov = 30.0 * kPi / 180.0;
    const dvec3 forward{0.0, std::sin(pitch), std::cos(pitch)};
    const dvec3 right{1.0, 0.0, 0.0};
    const dvec3 up = glm::cross(forward, right);
    return {{kEye.x, kEye.y, kEye.z},    {forward.x, forward.y, forward.z},
            {right.x, right.y, right.z}, {up.x, up.y, up.z},
            std::tan(half_fov),          double(width) / height};
}

SyntheticScene make_synthetic_scene(uint32_t width, uint32_t height) {
    SyntheticScene s;
    s.width = width;
    s.height = height;
    TextureData color{width, height, 1, std::vector<float>(size_t(width) * height * 4)};
    TextureData position = color;

    const SceneCamera cam = scene_camera(width, height);
    const dvec3 forward{cam.forward[0], cam.forward[1], cam.forward[2]};
    const dvec3 right{cam.right[0], cam.right[1], cam.right[2]};
    const dvec3 up{cam.up[0], cam.up[1], cam.up[2]};
    const double tan_half = cam.tan_half_fov_y, aspect = cam.aspect;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            // Pixel centre; row 0 is the top of the image.
            const double sx = (2.0 * (x + 0.5) / width - 1.0) * tan_half * aspect;
            const double sy = (1.0 - 2.0 * (y + 0.5) / height) * tan_half;
            const dvec3 d = glm::normalize(forward + right * sx + up * sy);
            const Hit hit = trace(kEye, d);
            const dvec3 p = kEye + d * hit.t;
            const dvec3 c = (hit.ground || hit.sphere) ? shade(hit, p) : sky(d);
            const size_t i = (size_t(y) * width + x) * 4;
            for (int k = 0; k < 3; ++k) {
                color.rgba[i + k] = static_cast<float>(c[k]);
                position.rgba[i + k] = static_cast<float>(p[k]);
            }
            color.rgba[i + 3] = 1.0f;
            position.rgba[i + 3] = static_cast<float>(hit.t);
        }
    s.textures["scene_color"] = std::move(color);
    s.textures["scene_position"] = std::move(position);
    s.uniforms["eye_position"] = {kEye.x, kEye.y, kEye.z};
    s.uniforms["water_level"] = {0.0};
    s.uniforms["sun_direction"] = {kSunTravel.x, kSunTravel.y, kSunTravel.z};
    s.uniforms["time"] = {0.0};
    add_foam_inputs(s);
    add_optics_inputs(s);
    add_wave_inputs(s);
    return s;
}

} // namespace watergen
