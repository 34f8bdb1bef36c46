// {{stamp}}

// Tessellated mesh path, hull stage: one quad patch of the wave grid. Control points are the
// corners (u, v) = (0, 0), (1, 0), (0, 1), (1, 1) in that order, each the undisplaced grid
// point, passed through to the domain stage. The patch-constant function computes the factors
// from the graph: SV_TessFactor 0..3 are the edges u = 0, v = 0, u = 1, v = 1, SV_InsideTessFactor
// the u and v directions, as GLSL's gl_TessLevelOuter / gl_TessLevelInner (glslang maps one to
// the other). The attributes state what mesh.tese.glsl states with
// layout(quads, fractional_odd_spacing, cw).
{{declarations}}

struct PatchPoint {
    float2 grid_xz : TEXCOORD0;
};

struct PatchFactors {
    float outer[4] : SV_TessFactor;
    float inner[2] : SV_InsideTessFactor;
};

{{prelude}}
PatchFactors mesh_patch_factors(InputPatch<PatchPoint, 4> patch_points) {
    float2 corner_0 = patch_points[0].grid_xz;
    float2 corner_1 = patch_points[1].grid_xz;
    float2 corner_2 = patch_points[2].grid_xz;
    float2 corner_3 = patch_points[3].grid_xz;
    {{body}}

    PatchFactors f;
    f.outer[0] = {{output_outer_0}};
    f.outer[1] = {{output_outer_1}};
    f.outer[2] = {{output_outer_2}};
    f.outer[3] = {{output_outer_3}};
    f.inner[0] = {{output_inner_0}};
    f.inner[1] = {{output_inner_1}};
    return f;
}

[domain("quad")]
[partitioning("fractional_odd")]
[outputtopology("triangle_cw")]
[outputcontrolpoints(4)]
[patchconstantfunc("mesh_patch_factors")]
PatchPoint main(InputPatch<PatchPoint, 4> patch_points, uint id : SV_OutputControlPointID) {
    PatchPoint o;
    o.grid_xz = patch_points[id].grid_xz;
    return o;
}
