#version 450
// Snapshot copy of templates/fullscreen.vert. Covers: the vertex stage every target emits.
// Full-screen triangle without vertex buffers: draw 3 vertices. vTexCoord (0,0) is the top-left
// of the output in Vulkan's y-down clip space; the GLSL and HLSL targets flip y so that stays true.
layout(location = 0) out vec2 vTexCoord;

void main() {
    vec2 uv = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    vTexCoord = uv;
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
