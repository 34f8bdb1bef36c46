#version 450
{{extensions}}
// {{stamp}}

// Tessellated geometry, vertex stage: one control point of a quad patch, its grid point
// morphed towards the coarser level as the mesh's vertex stage morphs it, passed on to the
// control stage. Nothing is displaced here; the evaluation stage displaces the points it
// generates. gl_Position is written for completeness (no later stage
// reads it).
{{declarations}}
layout(location = 0) out vec2 patch_grid_xz;

{{prelude}}
void main() {
    {{body}}

    gl_Position = {{output_position}};
    patch_grid_xz = {{output_grid_xz}};
}
