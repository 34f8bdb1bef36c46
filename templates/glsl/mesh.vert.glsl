#version 450
{{extensions}}
// {{stamp}}

// Mesh geometry: one vertex of the clipmap grid, morphed towards the coarser level and
// displaced by the wave model. The water fragment stage reads the displaced point, its grid
// point and its clip position (mesh_fragment_inputs(), in this order).
{{declarations}}
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec2 v_grid;
layout(location = 2) out vec4 v_clip;

{{prelude}}
void main() {
    {{body}}

    gl_Position = {{output_position}};
    v_world = {{output_world}};
    v_grid = {{output_grid}};
    v_clip = {{output_clip}};
}
