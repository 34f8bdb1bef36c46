#version 450
{{extensions}}
// {{stamp}}

// Tessellated mesh path, evaluation stage: one generated vertex of a quad patch. The grid
// point is the bilinear interpolation of the 4 control points (corners (0, 0), (1, 0), (0, 1),
// (1, 1)) at gl_TessCoord, written so it is exactly a corner at a corner (no mix(): a + t (b - a)
// need not give b at t = 1), hence the same point on both patches of a shared edge. Then the
// same wave displacement as the mesh vertex stage, and the same outputs (mesh.vert.glsl). Quads, fractional-odd spacing, clockwise:
// what the HLSL hull states with [domain("quad")], [partitioning("fractional_odd")],
// [outputtopology("triangle_cw")]. Clockwise in Vulkan's upper-left (u, v) domain, with u along
// +x and v along +z (up the screen), is counter-clockwise in the framebuffer: the water's upper
// side is front-facing under VK_FRONT_FACE_COUNTER_CLOCKWISE (measured on lavapipe,
// tests/eval/tessellated_render_test.cpp).
layout(quads, fractional_odd_spacing, cw) in;
{{declarations}}
layout(location = 0) in vec2 control_grid_xz[];
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec2 v_grid;
layout(location = 2) out vec4 v_clip;

{{prelude}}
void main() {
    float patch_u = gl_TessCoord.x;
    float patch_v = gl_TessCoord.y;
    vec2 grid_xz = (control_grid_xz[0] * (1.0 - patch_u) + control_grid_xz[1] * patch_u) *
                       (1.0 - patch_v) +
                   (control_grid_xz[2] * (1.0 - patch_u) + control_grid_xz[3] * patch_u) * patch_v;
    {{body}}

    gl_Position = {{output_position}};
    v_world = {{output_world}};
    v_grid = {{output_grid}};
    v_clip = {{output_clip}};
}
