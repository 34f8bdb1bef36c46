// {{stamp}}

// Mesh geometry: one vertex of the clipmap grid, morphed towards the coarser level and
// displaced by the wave model. Members after the position take locations 0, 1, 2 in order,
// like the GLSL skeleton's outputs (mesh_fragment_inputs()).
{{declarations}}

struct MeshVertex {
    float4 position : SV_Position;
    float3 v_world : TEXCOORD0;
    float2 v_grid : TEXCOORD1;
    float4 v_clip : TEXCOORD2;
};

{{prelude}}
MeshVertex main({{inputs}}) {
    {{body}}

    MeshVertex o;
    o.position = {{output_position}};
    o.v_world = {{output_world}};
    o.v_grid = {{output_grid}};
    o.v_clip = {{output_clip}};
    return o;
}
