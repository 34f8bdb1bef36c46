// {{stamp}}

// Numeric harness: one invocation evaluates one input tuple.
{{declarations}}
[[vk::binding(0, {{probe_set}})]] StructuredBuffer<float> probe_in : register(t0, space{{probe_set}});
[[vk::binding(1, {{probe_set}})]] RWStructuredBuffer<float> probe_out : register(u0, space{{probe_set}});

{{prelude}}
[numthreads(64, 1, 1)]
// probe_lane: quad differences (ddx, ddy) pair lanes 4k..4k+3.
void main(uint3 invocation : SV_DispatchThreadID, uint probe_lane : SV_GroupIndex) {
    uint in_base = invocation.x * {{input_stride}}u;
    uint out_base = invocation.x * {{output_stride}}u;
    {{reads}}

    {{body}}

    {{writes}}
}
