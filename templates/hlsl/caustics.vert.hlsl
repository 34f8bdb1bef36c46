// {{stamp}}

// Caustics pass (area ratio): one vertex of the grid over the water surface, moved to where the
// sunlight refracted through the surface meets the bottom. Members after the position take
// locations 0, 1, 2 in order, like the GLSL skeleton's outputs.
{{declarations}}

struct CausticsVertex {
    float4 position : SV_Position;
    float2 v_landing : TEXCOORD0;
    float2 v_offset : TEXCOORD1;
    float v_clamp : TEXCOORD2;
};

{{prelude}}
CausticsVertex main({{inputs}}) {
    {{body}}

    CausticsVertex o;
    o.position = {{output_position}};
    o.v_landing = {{output_landing}};
    o.v_offset = {{output_offset}};
    o.v_clamp = {{output_clamp}};
    return o;
}
