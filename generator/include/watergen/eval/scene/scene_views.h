// Named views of the synthetic scene (synthetic_scene.h): a camera and a sun each, chosen so
// that the features of the water pass show. One view cannot tell every choice apart (under the
// beach camera the sun's highlight is barely in frame, so the specular choices look alike);
// together they make every choice of every axis change the image (tests/render/
// scene_views_test.cpp measures which view separates which pair of choices).
//
// The scene stays one world (seabed, shoreline, submerged sphere, sky); a view moves the camera
// and the sun and may stand a sphere out of the water, so that the reflection nodes have scene
// geometry to reflect. `beach` is the camera and sun every render used before views existed.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace watergen {

// A sphere standing out of the water: lit like the rest of the scene, seen directly above the
// water, through it below, and mirrored in the planar reflection map.
struct StandingSphere {
    double centre[3]; // m
    double radius;    // m
    double albedo[3]; // linear rgb
};

struct SceneView {
    std::string name;        // e.g. "sun_glint"
    std::string description; // one line: what the view shows and which features it exercises
    double eye[3] = {0.0, 5.0, -7.0}; // m, above the water
    // Heading and elevation of the view direction: yaw 0 looks down +z, 90 down +x; pitch < 0
    // looks down. Right is horizontal, so the horizon stays level.
    double yaw_degrees = 0.0, pitch_degrees = -28.0;
    double fov_y_degrees = 60.0; // vertical field of view
    // Direction the sunlight travels (000's L; -L points at the sun); the scene normalises it.
    double sun_travel[3] = {-0.35, -0.75, 0.55};
    std::optional<StandingSphere> standing_sphere = std::nullopt;
    // Where the scene stands in the world (m): the whole scene, eye included, is moved by it.
    // Its content (seabed, spheres, sand ripples, the sky's points, the horizon) is defined
    // around the origin and placed at local + offset, the eye at eye + offset, the water plane
    // at y = offset y. The scene computes in double and rounds to float only what it stores in
    // textures (scene_position: the moved world positions, as an engine's absolute position
    // texture holds them). Wave, foam and texture patterns follow world positions, so they
    // differ between offsets; flat water looks the same at every offset.
    std::array<double, 3> world_offset{};
};

// Every view, `beach` first (the default of every command).
const std::vector<SceneView>& scene_views();
// The view named `name`, or nullptr.
const SceneView* find_scene_view(const std::string& name);
// The camera and sun of make_synthetic_scene(width, height).
const SceneView& beach_view();
// "beach, sun_glint, ...": the names in registry order, for help and errors.
std::string scene_view_names();

} // namespace watergen
