#include "watergen/water/mesh_shader.h"

#include "watergen/water/nodes/waves.h"
#include "watergen/water/scene_quantities.h"
#include "watergen/water/tessellated_mesh.h"

namespace watergen {

std::vector<std::pair<std::string, Type>> mesh_fragment_inputs() {
    return {{"v_world", Type::Vec3}, {"v_grid", Type::Vec2}, {"v_clip", Type::Vec4}};
}

std::vector<std::pair<std::string, Type>> mesh_vertex_inputs() {
    return {{"grid_xz", Type::Vec2}, {"grid_lod", Type::Vec3}};
}

// The one definition of each, which the water pass (water_shader.cpp) and every mesh stage
// read, bound to the scene quantities, so one block and one set of scene facts drive them all.
Expr scene_eye_position(Graph& g) {
    return bind(scene_quantity::eye_position, uniform(g, {.name = "eye_position",
                                                          .type = Type::Vec3,
                                                          .default_value = {0.0, 8.0, -30.0},
                                                          .min = -1e7,
                                                          .max = 1e7,
                                                          .unit = "m",
                                                          .seed = "000",
                                                          .host = {HostRule::FramePoint, {}}}));
}

Expr scene_water_level(Graph& g) {
    return bind(scene_quantity::water_level, uniform(g, {.name = "water_level",
                                                         .type = Type::Float,
                                                         .default_value = {0.0},
                                                         .min = -1e7,
                                                         .max = 1e7,
                                                         .unit = "m",
                                                         .seed = "000"}));
}

// A game's clock runs for hours and a persistent world's for months: time takes a year (365.25
// days); positions (the eye, the water level, the map windows) go 10,000 km from the world
// origin. Whether the waves hold that far is `watergen bench stability`'s question.
constexpr double kYearSeconds = 365.25 * 86400.0;

Expr scene_time(Graph& g) {
    return bind(scene_quantity::time, uniform(g, {.name = "time",
                                                  .type = Type::Float,
                                                  .default_value = {0.0},
                                                  .max = kYearSeconds,
                                                  .unit = "s",
                                                  .seed = "000"}));
}

Expr scene_sun_direction(Graph& g) {
    return bind(scene_quantity::sun_direction, uniform(g, {.name = "sun_direction",
                                                           .type = Type::Vec3,
                                                           .default_value = {-0.35, -0.75, 0.55},
                                                           .min = -1.0,
                                                           .max = 1.0,
                                                           .seed = "000"}));
}

Expr morphed_grid_point(Graph& g, Expr eye) {
    OriginScope scope(g, "geometry.morph");
    Expr xz = varying(g, "grid_xz", Type::Vec2);
    Expr lod = varying(g, "grid_lod", Type::Vec3);
    Expr start = uniform(g, {.name = "grid_morph_start",
                             .type = Type::Float,
                             .default_value = {1e6},
                             .max = 1e6,
                             .unit = "cells"});
    Expr end = uniform(g, {.name = "grid_morph_end",
                           .type = Type::Float,
                           .default_value = {2e6},
                           .max = 1e6,
                           .unit = "cells"});
    // A spacing of 0 (a hand-made grid without levels) never morphs rather than dividing by 0.
    Expr h = max(lod.z(), 1e-6);
    Expr d = max(abs(xz.x() - eye.x()), abs(xz.y() - eye.z())) / h;
    Expr t = named(saturate((d - start) / max(end - start, 1e-6)), "grid_morph");
    return named(xz + lod.xy() * t, "grid_point");
}

void displace_grid_point(Graph& g, const std::string& wave_model, Expr grid) {
    OriginScope scope(g, "geometry.displace");
    FullPrecisionScope full(g);
    Expr eye = scene_eye_position(g);
    Expr level = scene_water_level(g);
    Expr time = scene_time(g);
    Expr right = uniform(g, {.name = "mesh_camera_right",
                             .type = Type::Vec3,
                             .default_value = {1.0, 0.0, 0.0},
                             .min = -1.0,
                             .max = 1.0});
    Expr up = uniform(g, {.name = "mesh_camera_up",
                          .type = Type::Vec3,
                          .default_value = {0.0, 1.0, 0.0},
                          .min = -1.0,
                          .max = 1.0});
    Expr forward = uniform(g, {.name = "mesh_camera_forward",
                               .type = Type::Vec3,
                               .default_value = {0.0, 0.0, 1.0},
                               .min = -1.0,
                               .max = 1.0});
    Expr projection = uniform(g, {.name = "mesh_projection",
                                  .type = Type::Vec2,
                                  .default_value = {1.0, 1.0},
                                  .min = 1e-3,
                                  .max = 1e3});
    Expr near = uniform(g, {.name = "mesh_near",
                            .type = Type::Float,
                            .default_value = {0.1},
                            .min = 1e-4,
                            .max = 1e3,
                            .unit = "m"});
    // The screen pass' band limit (surface.h, pixel_footprint): no wave a pixel cannot show,
    // along the view where a grazing ray stretches the pixel most, at the point's undisplaced
    // place (pixel_angle * distance / |ray.y| = pixel_angle * distance^2 / height of the eye).
    // A pixel angle of 0 (the default) leaves the waves whole.
    Expr pixel_angle = uniform(g, {.name = "mesh_pixel_angle",
                                   .type = Type::Float,
                                   .default_value = {0.0},
                                   .max = 1.0,
                                   .unit = "rad"});
    Expr flat = vec3(grid.x(), level, grid.y()) - eye;
    Expr footprint =
        named(pixel_angle * dot(flat, flat) / max(eye.y() - level, 1e-6), "wave_footprint");
    Expr world;
    if (wave_model == "flat") {
        world = vec3(grid.x(), level, grid.y());
    } else if (wave_model == "sum_of_sines") {
        const SurfaceSample at = sum_of_sines_sample(g, grid, time, footprint, true, false);
        world = vec3(grid.x(), level + at.height, grid.y());
    } else if (wave_model == "gerstner") {
        Expr d = gerstner_point(g, grid, time, footprint).displacement;
        world = vec3(grid.x() + d.x(), level + d.y(), grid.y() + d.z());
    } else {
        g.error("geometry: no displacement for wave model '" + wave_model +
                "' (flat, sum_of_sines, gerstner)");
        return;
    }
    world = named(world, "world");
    Expr rel = world - eye;
    Expr depth = named(dot(rel, forward), "view_depth");
    // There is no depth buffer: the grid is drawn back to front (water_grid.h).
    Expr clip = named(
        vec4(dot(rel, right) * projection.x(), -dot(rel, up) * projection.y(), depth - near, depth),
        "clip");
    g.set_output("position", clip.id());
    g.set_output("world", world.id());
    g.set_output("grid", grid.id());
    g.set_output("clip", clip.id());
}

std::vector<const Graph*> MeshStages::graphs() const {
    if (tessellated()) return {&vertex, &control, &evaluation};
    return {&vertex};
}

std::vector<Graph*> MeshStages::graphs() {
    if (tessellated()) return {&vertex, &control, &evaluation};
    return {&vertex};
}

MeshStages build_mesh_stages(const std::string& geometry, const std::string& wave_model) {
    MeshStages m{geometry, Graph{}, Graph{}, Graph{}};
    if (geometry == "mesh") {
        OriginScope scope(m.vertex, "geometry.mesh");
        displace_grid_point(m.vertex, wave_model,
                            morphed_grid_point(m.vertex, scene_eye_position(m.vertex)));
    } else if (geometry == "tessellated") {
        build_patch_vertex(m.vertex);
        build_tess_control(m.control);
        OriginScope scope(m.evaluation, "geometry.tessellated");
        displace_grid_point(m.evaluation, wave_model, varying(m.evaluation, "grid_xz", Type::Vec2));
    } else {
        m.vertex.error("geometry: '" + geometry + "' has no mesh stages (mesh, tessellated)");
    }
    return m;
}

} // namespace watergen
