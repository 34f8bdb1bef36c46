#include "watergen/water/surface.h"

#include "watergen/water/scene_quantities.h"

namespace watergen {

// A field added to Surface must be added to surface_fields() too.
static_assert(sizeof(Surface) == sizeof(Graph*) + 26 * sizeof(Expr), "surface_fields() is stale");

std::vector<Expr*> surface_fields(Surface& s) {
    return {&s.uv,         &s.grid_xz,     &s.scene_rgb,     &s.scene_pos,      &s.to_scene,
            &s.eye,        &s.level,       &s.view_ray,      &s.scene_distance, &s.time,
            &s.sun_travel, &s.sun_color,   &s.surface_point, &s.path,           &s.depth,
            &s.is_water,   &s.wave_slope,  &s.normal,        &s.to_eye,         &s.n_dot_v,
            &s.refracted,  &s.water_color, &s.reflected,     &s.fresnel,        &s.specular,
            &s.color};
}

PlaneHit intersect_plane(const Surface& s, Expr height) {
    Expr ray_down = named(min(s.view_ray.y(), -1e-6), "view_ray_y");
    Expr t = named(max((height - s.eye.y()) / ray_down, 0.0), "surface_distance");
    return {named(s.eye + s.view_ray * t, "surface_point"), t};
}

Expr pixel_angle(const Surface& s) {
    return named(max(length(ddx(s.view_ray)), length(ddy(s.view_ray))), "pixel_angle");
}

Expr pixel_footprint(const Surface& s) {
    // |ray.y| is 0 for a horizontal ray: guarded as in the surface search.
    Expr ray_down = max(-s.view_ray.y(), 1e-6);
    return named(pixel_angle(s) * length(s.surface_point - s.eye) / ray_down, "pixel_footprint");
}

void set_water_column(Surface& s, Expr surface_distance) {
    s.path = named(max(s.scene_distance - surface_distance, 0.0), "water_path");
    s.depth = bind(scene_quantity::water_depth,
                   named(max(s.surface_point.y() - s.scene_pos.y(), 0.0), "water_depth"));
    // The eye is above the water: a ray going up never reaches it (its clamped plane hit lies
    // millions of metres away and would otherwise count the sky as water).
    s.is_water = (s.scene_pos.y() < s.surface_point.y()) && (s.view_ray.y() < 0.0);
}

} // namespace watergen
