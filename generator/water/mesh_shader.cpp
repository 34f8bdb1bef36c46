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

// Same names and defaults as the water pass (water_shader.cpp), bound to the same scene
// quantities, so one block and one set of scene facts drive every stage.
Expr mesh_eye_position(Graph& g) {
    return bind(
        scene_quantity::eye_position,
        uniform(g, {"eye_position", Type::Vec3, {0.0, 8.0, -30.0}, -1e5, 1e5, "m", "000", ""}));
}

Expr mesh_water_level(Graph& g) {
    return bind(scene_quantity::water_level,
                uniform(g, {"water_level", Type::Float, {0.0}, -1e5, 1e5, "m", "000", ""}));
}

Expr mesh_time(Graph& g) {
    return bind(scene_quantity::time,
                uniform(g, {"time", Type::Float, {0.0}, 0.0, 86400.0, "s", "000", ""}));
}

Expr morphed_grid_point(Graph& g, Expr eye) {
    OriginScope scope(g, "geometry.morph");
    Expr xz = varying(g, "grid_xz", Type::Vec2);
    Expr lod = varying(g, "grid_lod", Type::Vec3);
    Expr start = uniform(g, {"grid_morph_start", Type::Float, {1e6}, 0.0, 1e6, "cells", "", ""});
    Expr end = uniform(g, {"grid_morph_end", Type::Float, {2e6}, 0.0, 1e6, "cells", "", ""});
    // A spacing of 0 (a hand-made grid without levels) never morphs rather than dividing by 0.
    Expr h = max(lod.z(), 1e-6);
    Expr d = max(abs(xz.x() - eye.x()), abs(xz.y() - eye.z())) / h;
    Expr t = named(saturate((d - start) / max(end - start, 1e-6)), "grid_morph");
    return named(xz + lod.xy() * t, "grid_point");
}

void displace_grid_point(Graph& g, const std::string& wave_model, Expr grid) {
    OriginScope scope(g, "geometry.displace");
    FullPrecisionScope full(g);
    Expr eye = mesh_eye_position(g);
    Expr level = mesh_water_level(g);
    Expr time = mesh_time(g);
    Expr right =
        uniform(g, {"mesh_camera_right", Type::Vec3, {1.0, 0.0, 0.0}, -1.0, 1.0, "", "", ""});
    Expr up = uniform(g, {"mesh_camera_up", Type::Vec3, {0.0, 1.0, 0.0}, -1.0, 1.0, "", "", ""});
    Expr forward =
        uniform(g, {"mesh_camera_forward", Type::Vec3, {0.0, 0.0, 1.0}, -1.0, 1.0, "", "", ""});
    Expr projection =
        uniform(g, {"mesh_projection", Type::Vec2, {1.0, 1.0}, 1e-3, 1e3, "", "", ""});
    Expr near = uniform(g, {"mesh_near", Type::Float, {0.1}, 1e-4, 1e3, "m", "", ""});
    // The screen pass' band limit (surface.h, pixel_footprint): no wave a pixel cannot show,
    // along the view where a grazing ray stretches the pixel most, at the point's undisplaced
    // place (pixel_angle * distance / |ray.y| = pixel_angle * distance^2 / height of the eye).
    // A pixel angle of 0 (the default) leaves the waves whole.
    Expr pixel_angle =
        uniform(g, {"mesh_pixel_angle", Type::Float, {0.0}, 0.0, 1.0, "rad", "", ""});
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
                            morphed_grid_point(m.vertex, mesh_eye_position(m.vertex)));
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
