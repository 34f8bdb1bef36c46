#version 450
{{extensions}}
// {{stamp}}

// Caustics pass (area ratio): one vertex of the grid over the water surface, moved to where the
// sunlight refracted through the surface meets the bottom. The fragment stage takes the landing
// point, the beam point's offset from it and the clamp, in this order.
{{declarations}}
layout(location = 0) out vec2 v_landing;
layout(location = 1) out vec2 v_offset;
layout(location = 2) out float v_clamp;

{{prelude}}
void main() {
    {{body}}

    gl_Position = {{output_position}};
    v_landing = {{output_landing}};
    v_offset = {{output_offset}};
    v_clamp = {{output_clamp}};
}
