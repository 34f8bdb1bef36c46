#include "watergen/water/tessellated_mesh.h"

#include <string>

#include "watergen/ir/core/dsl.h"
#include "watergen/water/mesh_shader.h"

namespace watergen {

void build_patch_vertex(Graph& g) {
    OriginScope scope(g, "geometry.patch_vertex");
    Expr grid = morphed_grid_point(g, scene_eye_position(g));
    g.set_output("position", vec4(grid.x(), constant(g, 0.0), grid.y(), constant(g, 1.0)).id());
    g.set_output("grid_xz", grid.id());
}

void build_tess_control(Graph& g) {
    OriginScope scope(g, "geometry.tess_control");
    Expr corners[4];
    for (int i = 0; i < 4; ++i)
        corners[i] = varying(g, "corner_" + std::to_string(i), Type::Vec2);
    Expr eye = scene_eye_position(g);
    Expr level = scene_water_level(g);
    Expr scale = uniform(g, {.name = "tess_scale",
                             .type = Type::Float,
                             .default_value = {40.0},
                             .max = 1e4,
                             .unit = "m"});
    Expr limit = uniform(g, {.name = "tess_max",
                             .type = Type::Float,
                             .default_value = {16.0},
                             .min = 1.0,
                             .max = kMaxTessellationFactor});
    // The range is not enforced where the block is filled, so the shader bounds it itself: a
    // tess_max of 100 (or 0) still gives factors in [1, 64].
    Expr top = named(clamp(limit, 1.0, kMaxTessellationFactor), "tess_limit");
    auto edge = [&](Expr a, Expr b, const char* name) {
        Expr mid = (a + b) * 0.5;
        Expr distance = length(vec3(mid.x(), level, mid.y()) - eye);
        // The floor keeps the quotient finite with the eye on the edge (the factor is then
        // the limit anyway).
        return named(clamp(scale / max(distance, 1e-3), constant(g, 1.0), top), name);
    };
    // Edges u = 0, v = 0, u = 1, v = 1 over corners (0,0), (1,0), (0,1), (1,1).
    Expr outer_0 = edge(corners[0], corners[2], "edge_u0");
    Expr outer_1 = edge(corners[0], corners[1], "edge_v0");
    Expr outer_2 = edge(corners[1], corners[3], "edge_u1");
    Expr outer_3 = edge(corners[2], corners[3], "edge_v1");
    g.set_output("outer_0", outer_0.id());
    g.set_output("outer_1", outer_1.id());
    g.set_output("outer_2", outer_2.id());
    g.set_output("outer_3", outer_3.id());
    // Inner 0 subdivides along u, as the edges v = 0 and v = 1 do; inner 1 along v.
    g.set_output("inner_0", max(outer_1, outer_3).id());
    g.set_output("inner_1", max(outer_0, outer_2).id());
}

} // namespace watergen
