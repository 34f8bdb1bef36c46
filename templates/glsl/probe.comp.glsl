#version 450
{{extensions}}
// {{stamp}}

// Numeric harness: one invocation evaluates one input tuple.
layout(local_size_x = 64) in;

{{declarations}}
layout(set = {{probe_set}}, binding = 0, std430) readonly buffer ProbeInputs { float probe_in[]; };
layout(set = {{probe_set}}, binding = 1, std430) writeonly buffer ProbeOutputs { float probe_out[]; };

{{prelude}}
void main() {
    uint in_base = gl_GlobalInvocationID.x * {{input_stride}}u;
    uint out_base = gl_GlobalInvocationID.x * {{output_stride}}u;
    uint probe_lane = gl_LocalInvocationIndex; // quad differences (ddx, ddy) pair lanes 4k..4k+3
    {{reads}}

    {{body}}

    {{writes}}
}
