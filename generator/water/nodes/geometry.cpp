// The geometry axis: how the water reaches the screen. The screen pass (seed 000's
// post-process formulation) finds the surface along each pixel's view ray; a mesh (seeds 001,
// 004) is a camera-centred grid displaced in the vertex stage; a tessellated mesh subdivides
// patches near the eye and displaces them in the evaluation (domain) stage. Either way the
// fragment stage shades with every node; a mesh fragment starts from the rasterised point
// (water/mesh_shader.h writes the stages before it).
#include "axis_tables.h"
#include "watergen/water/mesh_shader.h"
#include "watergen/water/surface.h"

namespace watergen {

namespace {

// A mesh fragment: the vertex (or evaluation) stage's varyings, in the locations
// mesh_fragment_inputs() gives them.
void compose_mesh_fragment(Surface& s) {
    Graph& g = s.g;
    OriginScope scope(g, "geometry.mesh");
    FullPrecisionScope full(g);
    Expr world = varying(g, "v_world", Type::Vec3);
    Expr grid = varying(g, "v_grid", Type::Vec2);
    Expr clip = varying(g, "v_clip", Type::Vec4);
    // Clip coordinates interpolate exactly (perspective-correct, and linear in the world on
    // a triangle): x / w, y / w are the fragment centre's NDC, hence the screen pass's uv.
    s.uv = named(clip.xy() / clip.w() * 0.5 + 0.5, "mesh_uv");
    s.surface_point = named(world, "surface_point");
    s.grid_xz = named(grid, "mesh_grid_xz");
}

} // namespace

AxisInfo geometry_axis() {
    const std::vector<std::string> closed_forms = {"flat", "sum_of_sines", "gerstner"};
    const std::string why = "the vertex stage displaces the grid by a closed-form wave model";
    AxisInfo axis{
        "geometry",
        "screen_pass",
        {
            {.name = "screen_pass",
             .seed = "000",
             .description = "full-screen pass: the surface found along each pixel's view ray",
             .compose = [](Surface& s) { s.uv = varying(s.g, "v_uv", Type::Vec2); }},
            {.name = "mesh",
             .seed = "004",
             .description = "camera-centred clipmap grid displaced in the vertex stage",
             .compose = &compose_mesh_fragment,
             .requirements = {{"waves", closed_forms, why}}},
            {.name = "tessellated",
             .seed = "004",
             .description = "clipmap patches tessellated by distance, displaced in the "
                            "evaluation (domain) stage",
             .compose = &compose_mesh_fragment,
             .scene_needs = {{SceneFact::CameraNear, "", "the mesh geometry draws the same"}},
             .requirements = {{"waves",
                               {"sum_of_sines", "gerstner"},
                               "tessellation refines a moving surface; a plane needs none"}}},
        }};
    // Keys and file names of every variant from before the axis stay as they were.
    axis.keyed_at_default = false;
    axis.permutation_only = true; // the stages before the fragment differ
    return axis;
}

} // namespace watergen
