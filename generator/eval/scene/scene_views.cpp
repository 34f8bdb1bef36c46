#include "watergen/eval/scene/scene_views.h"

#include "watergen/ir/core/text.h"

namespace watergen {

const std::vector<SceneView>& scene_views() {
    // Seabed y = -1 - 0.25 z: the shoreline at z = -4, 1 m deep at z = 0, 10 m at z = 36.
    static const std::vector<SceneView> list = {
        {"beach",
         "from above the beach over the shoreline out to sea, sun high behind the camera (the "
         "default)"},
        // The sun 17 degrees up straight ahead: its mirror image on flat water lies 3 degrees
        // under the centre of the image, 13 m out over 2.8 m of water.
        {.name = "sun_glint",
         .description = "towards a low sun: its reflection in the waves (specular, Fresnel)",
         .eye = {0.0, 4.0, -6.0},
         .pitch_degrees = -14.0,
         .sun_travel = {0.0, -0.3, -1.0}},
        // Rays up to 24 degrees under the horizon, which runs just above the middle of the image.
        {.name = "grazing",
         .description = "low over the water to the horizon: grazing angles (Fresnel, waves, "
                        "reflection)",
         .eye = {0.0, 1.2, 2.0},
         .pitch_degrees = -4.0,
         .fov_y_degrees = 40.0,
         .sun_travel = {0.6, -0.5, 0.3}},
        // Looking back up the beach: 0.8 m of water under the bottom edge, the shoreline
        // across the middle, dry sand above; the beach's sun, high over the beach ahead.
        {.name = "shoreline",
         .description = "from the shallows back at the beach: shallow water, the shoreline, "
                        "shore foam and the soft shore",
         .eye = {0.0, 2.5, 1.0},
         .yaw_degrees = 180.0,
         .pitch_degrees = -30.0,
         .fov_y_degrees = 50.0},
        // 8.5 m of water straight under the bottom edge, 16 m under the top; the sun nearly
        // overhead, its highlight in frame.
        {.name = "open_water",
         .description = "deep water seen from high above, the sun nearly overhead: extinction, "
                        "refraction, normals, the sun's highlight",
         .eye = {0.0, 25.0, 30.0},
         .pitch_degrees = -65.0,
         .fov_y_degrees = 50.0,
         .sun_travel = {0.2, -0.9, 0.3}},
        // A buoy 12 m ahead over 3.5 m of water, 3.8 m tall above it and 0.2 m under: its
        // mirror image reaches down the water to 5 m from the camera.
        {.name = "reflection",
         .description = "a red buoy standing out of the water and its mirror image (planar "
                        "reflection against the sky's)",
         .eye = {0.0, 3.0, -2.0},
         .pitch_degrees = -8.0,
         .sun_travel = {-0.5, -0.6, 0.4},
         .standing_sphere = StandingSphere{{0.0, 1.8, 10.0}, 2.0, {0.8, 0.15, 0.1}}},
    };
    return list;
}

const SceneView* find_scene_view(const std::string& name) {
    for (const auto& v : scene_views())
        if (v.name == name) return &v;
    return nullptr;
}

const SceneView& beach_view() {
    return scene_views().front();
}

std::string scene_view_names() {
    return join(scene_views(), [](const SceneView& v) { return v.name; });
}

} // namespace watergen
