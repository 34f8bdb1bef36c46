// {{stamp}}

// One triangle covering the viewport; v_uv = (0, 0) at the top-left pixel corner, matching
// texture row 0 and Vulkan's framebuffer origin.
float4 main(uint vertex_id : SV_VertexID, out float2 v_uv : TEXCOORD0) : SV_Position {
    v_uv = float2((vertex_id << 1) & 2, vertex_id & 2);
    return float4(v_uv * 2.0 - 1.0, 0.0, 1.0);
}
