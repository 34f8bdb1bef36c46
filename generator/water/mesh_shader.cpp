#include "watergen/water/mesh_shader.h"

#include <cmath>

#include "watergen/ir/dsl.h"
#include "watergen/water/nodes/waves.h"
#include "watergen/water/scene_quantities.h"

namespace watergen {

namespace {

void build_vertex(Graph& g, const std::string& model) {
    OriginScope scope(g, "mesh.vertex");
    Expr grid = varying(g, "grid_xz", Type::Vec2);
    Expr eye = mesh_eye_position(g);
    Expr level = mesh_water_level(g);
    Expr time = bind(scene_quantity::time,
                     uniform(g, {"time", Type::Float, {0.0}, 0.0, 86400.0, "s", "000", ""}));
    Expr right =
        uniform(g, {"mesh_camera_right", Type::Vec3, {1.0, 0.0, 0.0}, -1.0, 1.0, "", "", ""});
    Expr up = uniform(g, {"mesh_camera_up", Type::Vec3, {0.0, 1.0, 0.0}, -1.0, 1.0, "", "", ""});
    Expr forward =
        uniform(g, {"mesh_camera_forward", Type::Vec3, {0.0, 0.0, 1.0}, -1.0, 1.0, "", "", ""});
    Expr projection =
        uniform(g, {"mesh_projection", Type::Vec2, {1.0, 1.0}, 1e-3, 1e3, "", "", ""});
    Expr near = uniform(g, {"mesh_near", Type::Float, {0.1}, 1e-4, 1e3, "m", "", ""});
    Expr world, normal;
    if (model == "sum_of_sines") {
        const SurfaceSample at = sum_of_sines_sample(g, grid, time, Expr(), true, true);
        world = vec3(grid.x(), level + at.height, grid.y());
        normal = sum_of_sines_normal_from(g, at.slope);
    } else if (model == "gerstner") {
        const GerstnerPoint at = gerstner_point(g, grid, time, Expr());
        Expr d = at.displacement;
        world = vec3(grid.x() + d.x(), level + d.y(), grid.y() + d.z());
        normal = at.normal;
    } else {
        g.error("mesh: no vertex displacement for wave model '" + model +
                "' (sum_of_sines, gerstner)");
        return;
    }
    world = named(world, "world");
    Expr rel = world - eye;
    Expr depth = named(dot(rel, forward), "view_depth");
    // Vulkan clip space: x right, y down, z = depth - near (so 0 <= z <= w from the near plane
    // on; there is no depth buffer, the grid is drawn back to front instead).
    Expr clip =
        vec4(dot(rel, right) * projection.x(), -dot(rel, up) * projection.y(), depth - near, depth);
    g.set_output("position", clip.id());
    g.set_output("normal", normal.id());
    g.set_output("world", world.id());
}

void build_fragment(Graph& g) {
    OriginScope scope(g, "mesh.fragment");
    Expr normal_in = varying(g, "v_normal", Type::Vec3);
    Expr world = varying(g, "v_world", Type::Vec3);
    // Interpolation shortens the unit normals; renormalise (never zero between nearby normals
    // of a height field, but keep the guard).
    Expr n = safe_normalize(normal_in, constant(g, {0.0, 1.0, 0.0}));
    // Towards the synthetic scene's sun (its travel direction (-0.35, -0.75, 0.55), negated).
    const double len = std::sqrt(0.35 * 0.35 + 0.75 * 0.75 + 0.55 * 0.55);
    Expr to_sun = constant(g, {0.35 / len, 0.75 / len, -0.55 / len});
    Expr lambert = named(saturate(dot(n, to_sun)), "n_dot_l");
    Expr rgb = (n * 0.5 + 0.5) * (0.35 + 0.65 * lambert);
    // Crests lighter than troughs: reads the world position, so every varying is consumed.
    rgb = rgb * (1.0 + 0.25 * clamp(world.y(), -1.0, 1.0));
    g.set_output("color", vec4(rgb, constant(g, 1.0)).id());
}

} // namespace

// Same names and defaults as the post-process pass (water_shader.cpp), so one uniform set
// drives both. Bound to the scene quantities as in the water pass, so scene facts would reach
// them.
Expr mesh_eye_position(Graph& g) {
    return bind(
        scene_quantity::eye_position,
        uniform(g, {"eye_position", Type::Vec3, {0.0, 8.0, -30.0}, -1e5, 1e5, "m", "000", ""}));
}

Expr mesh_water_level(Graph& g) {
    return bind(scene_quantity::water_level,
                uniform(g, {"water_level", Type::Float, {0.0}, -1e5, 1e5, "m", "000", ""}));
}

MeshShader build_mesh_shader(const std::string& wave_model) {
    MeshShader m{wave_model, Graph{}, Graph{}};
    build_vertex(m.vertex, wave_model);
    build_fragment(m.fragment);
    return m;
}

} // namespace watergen
