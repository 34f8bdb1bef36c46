#version 450
{{extensions}}
// {{stamp}}

// Caustics pass (photon splatting, seed 002): one photon, a point of the grid over the water
// surface moved to where the sunlight refracted through it meets the bottom, one pixel wide.
{{declarations}}
layout(location = 0) out float v_weight;

{{prelude}}
void main() {
    {{body}}

    gl_Position = {{output_position}};
    gl_PointSize = 1.0;
    v_weight = {{output_weight}};
}
