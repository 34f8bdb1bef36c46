#version 450
// {{stamp}}

// One triangle covering the viewport; v_uv = (0, 0) at the top-left pixel corner, matching
// texture row 0 and Vulkan's framebuffer origin.
layout(location = 0) out vec2 v_uv;

void main() {
    v_uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(v_uv * 2.0 - 1.0, 0.0, 1.0);
}
