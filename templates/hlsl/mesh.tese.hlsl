// {{stamp}}

// Tessellated mesh path, domain stage: one generated vertex of a quad patch. The grid point is
// the bilinear interpolation of the 4 control points (corners (0, 0), (1, 0), (0, 1), (1, 1))
// at SV_DomainLocation, written as mesh.tese.glsl writes it (exactly a corner at a corner, no
// lerp()), then the same wave displacement as the mesh vertex stage. The hull
// (mesh.tesc.hlsl) states the partitioning and the winding. Members after the position take
// locations 0, 1, 2 in order, like the GLSL skeleton's outputs.
{{declarations}}

struct PatchPoint {
    float2 grid_xz : TEXCOORD0;
};

struct MeshVertex {
    float4 position : SV_Position;
    float3 v_world : TEXCOORD0;
    float2 v_grid : TEXCOORD1;
    float4 v_clip : TEXCOORD2;
};

{{prelude}}
[domain("quad")]
MeshVertex main(const OutputPatch<PatchPoint, 4> patch_points, float2 domain : SV_DomainLocation) {
    float patch_u = domain.x;
    float patch_v = domain.y;
    float2 grid_xz = (patch_points[0].grid_xz * (1.0 - patch_u) + patch_points[1].grid_xz * patch_u) *
                         (1.0 - patch_v) +
                     (patch_points[2].grid_xz * (1.0 - patch_u) + patch_points[3].grid_xz * patch_u) *
                         patch_v;
    {{body}}

    MeshVertex o;
    o.position = {{output_position}};
    o.v_world = {{output_world}};
    o.v_grid = {{output_grid}};
    o.v_clip = {{output_clip}};
    return o;
}
