// {{stamp}}

// Mesh path: one vertex of the wave grid. The wave model displaces the grid point and gives
// its analytic normal; both reach the mesh fragment stage interpolated. Members after the
// position take locations 0, 1 in order, like the GLSL skeleton's outputs.
{{declarations}}

struct MeshVertex {
    float4 position : SV_Position;
    float3 v_normal : TEXCOORD0;
    float3 v_world : TEXCOORD1;
};

{{prelude}}
MeshVertex main({{inputs}}) {
    {{body}}

    MeshVertex o;
    o.position = {{output_position}};
    o.v_normal = {{output_normal}};
    o.v_world = {{output_world}};
    return o;
}
