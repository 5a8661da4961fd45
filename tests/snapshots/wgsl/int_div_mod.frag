#version 450
// Covers: int / and % with negative operands (uniform and constant), float mod() of negatives
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    ivec4 q = ivec4(p.i.x / p.i.y, p.i.z / p.i.w, p.i.x % p.i.y, p.i.z % -3);
    vec4 m = vec4(mod(p.a.x, p.a.y), mod(p.a.z, p.a.w), mod(-vTexCoord.x, 0.25), mod(p.a.x, -2.0));
    fragColor = vec4(q) + m;
}
