#version 450
{{extensions}}
// {{stamp}}

// Mesh path: one vertex of the wave grid. The wave model displaces the grid point and gives
// its analytic normal; both reach the mesh fragment stage interpolated.
{{declarations}}
layout(location = 0) out vec3 v_normal;
layout(location = 1) out vec3 v_world;

{{prelude}}
void main() {
    {{body}}

    gl_Position = {{output_position}};
    v_normal = {{output_normal}};
    v_world = {{output_world}};
}
