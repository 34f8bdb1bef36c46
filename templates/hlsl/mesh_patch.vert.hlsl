// {{stamp}}

// Tessellated geometry, vertex stage: one control point of a quad patch, its grid point
// morphed towards the coarser level as the mesh's vertex stage morphs it, passed on to the
// hull stage (location 0, like mesh_patch.vert.glsl). Nothing is
// displaced here; the domain stage displaces the points it generates. The position is written
// for completeness (no later stage reads it).
{{declarations}}

struct PatchVertex {
    float4 position : SV_Position;
    float2 grid_xz : TEXCOORD0;
};

{{prelude}}
PatchVertex main({{inputs}}) {
    {{body}}

    PatchVertex o;
    o.position = {{output_position}};
    o.grid_xz = {{output_grid_xz}};
    return o;
}
