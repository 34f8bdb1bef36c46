#version 450
{{extensions}}
// {{stamp}}

// Tessellated mesh path, control stage: one quad patch of the wave grid. Control points are
// the corners (u, v) = (0, 0), (1, 0), (0, 1), (1, 1) in that order, each the undisplaced grid
// point, passed through to the evaluation stage. The factors come from the graph: outer levels
// 0..3 are the edges u = 0, v = 0, u = 1, v = 1 (GLSL 4.50, 11.2.2.2 "Quad Tessellation"), the
// inner levels the u and v directions. Domain, spacing and winding are stated by the
// evaluation stage (mesh.tese.glsl).
layout(vertices = 4) out;
{{declarations}}
layout(location = 0) in vec2 patch_grid_xz[];
layout(location = 0) out vec2 control_grid_xz[];

{{prelude}}
void main() {
    control_grid_xz[gl_InvocationID] = patch_grid_xz[gl_InvocationID];
    // The patch's levels once per patch: every invocation would write the same values.
    if (gl_InvocationID == 0) {
        vec2 corner_0 = patch_grid_xz[0];
        vec2 corner_1 = patch_grid_xz[1];
        vec2 corner_2 = patch_grid_xz[2];
        vec2 corner_3 = patch_grid_xz[3];
        {{body}}

        gl_TessLevelOuter[0] = {{output_outer_0}};
        gl_TessLevelOuter[1] = {{output_outer_1}};
        gl_TessLevelOuter[2] = {{output_outer_2}};
        gl_TessLevelOuter[3] = {{output_outer_3}};
        gl_TessLevelInner[0] = {{output_inner_0}};
        gl_TessLevelInner[1] = {{output_inner_1}};
    }
}
