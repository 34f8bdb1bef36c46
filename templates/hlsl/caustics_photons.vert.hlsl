// {{stamp}}

// Caustics pass (photon splatting, seed 002): one photon, a point of the grid over the water
// surface moved to where the sunlight refracted through it meets the bottom, one pixel wide.
// Members after the position and point size take location 0, like the GLSL skeleton's output.
{{declarations}}

struct PhotonVertex {
    float4 position : SV_Position;
    [[vk::builtin("PointSize")]] float point_size : PSIZE;
    float v_weight : TEXCOORD0;
};

{{prelude}}
PhotonVertex main({{inputs}}) {
    {{body}}

    PhotonVertex o;
    o.position = {{output_position}};
    o.point_size = 1.0;
    o.v_weight = {{output_weight}};
    return o;
}
