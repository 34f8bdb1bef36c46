// Geometry and lighting shared by the synthetic scene's textures: what the camera sees
// (synthetic_scene.cpp) and what the mirrored camera of the planar reflection sees
// (scene_optics_inputs.cpp). Private to render/.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include <glm/glm.hpp>

namespace watergen::scene_geometry {

using glm::dvec3;

inline constexpr double kPi = std::numbers::pi;

// A scene point defined around the origin placed at local + the world offset (scene_views.h),
// and back. Exactly the local value where the offset is 0, so that a scene at offset 0 keeps
// its bytes (-0 + 0 would be +0).
inline double placed(double local, double offset) {
    return offset == 0.0 ? local : local + offset;
}
inline double unplaced(double world, double offset) {
    return offset == 0.0 ? world : world - offset;
}
inline dvec3 placed(const dvec3& local, const std::array<double, 3>& offset) {
    return {placed(local.x, offset[0]), placed(local.y, offset[1]), placed(local.z, offset[2])};
}
inline dvec3 unplaced(const dvec3& world, const std::array<double, 3>& offset) {
    return {unplaced(world.x, offset[0]), unplaced(world.y, offset[1]),
            unplaced(world.z, offset[2])};
}
inline bool has_offset(const std::array<double, 3>& offset) {
    return offset[0] != 0.0 || offset[1] != 0.0 || offset[2] != 0.0;
}

// Where the unit ray o + t d enters the sphere: its near side (t > 0), 0 when o lies inside it,
// nothing when the sphere is missed or behind o.
inline std::optional<double> sphere_entry(const dvec3& o, const dvec3& d, const dvec3& centre,
                                          double radius) {
    const dvec3 oc = o - centre;
    const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
    const double disc = b * b - c;
    if (disc <= 0.0) return std::nullopt;
    const double root = std::sqrt(disc), near = -b - root;
    if (-b + root <= 0.0) return std::nullopt;
    return std::max(near, 0.0);
}

// Every surface of the scene is lit alike: Lambert under the sun plus an ambient term.
inline dvec3 sunlit(const dvec3& albedo, const dvec3& normal, const dvec3& to_sun) {
    const double lambert = std::max(glm::dot(normal, to_sun), 0.0);
    return albedo * (0.25 + 0.9 * lambert);
}

} // namespace watergen::scene_geometry
