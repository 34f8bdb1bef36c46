// What the fullscreen water pass knows at one pixel, filled in axis by axis. Each choice of the
// axis registry (axis_registry.h) composes into it: it reads the fields set by the axes before
// it and sets its own; water_shader.cpp runs the axes in the order below (compose_choice).
#pragma once

#include <string>
#include <vector>

#include "watergen/ir/core/dsl.h"

namespace watergen {

struct Surface {
    explicit Surface(Graph& graph) : g(graph) {}
    Graph& g;

    // Set by the skeleton (water_shader.cpp) before any axis runs; scene_pos and to_scene by
    // the scene_input axis, which the skeleton composes after the geometry axis.
    // uv by the geometry axis, first; a mesh's fragment also sets grid_xz and surface_point
    // (the rasterised point), which the waves axis then takes instead of searching.
    Expr uv;             // vec2, screen position in [0, 1]^2, (0, 0) top-left
    Expr grid_xz;        // vec2, the mesh's undisplaced grid point, m; invalid in the screen pass
    Expr scene_rgb;      // vec3, lit scene colour at uv (what lies under / behind the water)
    Expr scene_pos;      // vec3, world position of the scene at uv, m
    Expr to_scene;       // vec3, scene_pos - eye, m (a camera-relative input has it exactly)
    Expr eye;            // vec3, camera position, m
    Expr level;          // float, height of the undisturbed water plane, m
    Expr view_ray;       // vec3, unit, from the eye towards scene_pos
    Expr scene_distance; // float, |scene_pos - eye|, m
    Expr time;           // float, s
    Expr sun_travel;     // vec3, unit direction the sunlight travels (000: L; -L points at the sun)
    Expr sun_color;      // vec3, sun radiance scale

    // 1. waves: where the view ray meets the water surface.
    Expr surface_point; // vec3, m
    Expr path;          // float, water path along the view ray from surface to scene, m (>= 0)
    Expr depth;         // float, vertical water depth under the surface point, m (>= 0)
    Expr is_water;      // bool, the pixel shows water (scene below the surface)
    Expr
        wave_slope; // vec2 (dh/dx, dh/dz) at surface_point when the wave model has it, else invalid

    // 2. normals
    Expr normal;  // vec3, unit, surface normal at surface_point
    Expr to_eye;  // vec3, unit, V (set by the skeleton after normals)
    Expr n_dot_v; // float, c = dot(N, V)

    // 3. refraction: colour seen through the surface, before extinction; the caustics axis
    // (composed next, last in a variant key) scales it by the light focused on the bottom.
    Expr refracted; // vec3
    // 4. extinction: what the water column does to it.
    Expr water_color; // vec3
    // 5. reflection
    Expr reflected; // vec3
    // 6. fresnel
    Expr fresnel; // float in [0, 1]
    // 7. specular
    Expr specular; // vec3, added after the Fresnel blend
    // 8. foam and 9. shore work on the composed colour.
    Expr color; // vec3
};

// Every field of `s`, in declaration order: what an axis composed as a switch (axis_switch.cpp)
// carries into and out of its cases.
std::vector<Expr*> surface_fields(Surface& s);

// Where the view ray meets the horizontal plane y = height: the point, and its distance along
// the ray (clamped to >= 0). A water pixel's ray points down; its y is clamped to <= -1e-6 so
// a horizontal ray never divides by zero (000's pitfall).
struct PlaneHit {
    Expr point;
    Expr distance;
};
PlaneHit intersect_plane(const Surface& s, Expr height);

// Radians per pixel (view_ray is unit, its screen derivatives give the angle a pixel spans):
// the band limit of the wave models and of the height-map normals.
Expr pixel_angle(const Surface& s);
// A pixel's extent (m) on the water at surface_point, along the view direction where a grazing
// ray stretches it most; needs surface_point.
Expr pixel_footprint(const Surface& s);

// Sets path, depth and is_water from surface_point (for wave models that move the surface).
void set_water_column(Surface& s, Expr surface_distance);

} // namespace watergen
