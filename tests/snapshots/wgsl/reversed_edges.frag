#version 450
// Covers: smoothstep and clamp with reversed constant edges next to ordered ones
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    float x = vTexCoord.x;
    fragColor = vec4(smoothstep(0.85, 0.4, x), smoothstep(0.4, 0.85, x), clamp(x, 0.75, 0.25), clamp(x, 0.25, 0.75));
}
