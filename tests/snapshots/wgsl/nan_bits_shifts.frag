#version 450
// Covers: isnan/isinf, ordered and unordered compares, bitcasts and arithmetic vs logical shifts
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    float n = p.a.x;
    uint bits = floatBitsToUint(vTexCoord.x) >> 16;
    int shifted = p.i.y >> 2;
    fragColor = vec4(isnan(n) ? 1.0 : 0.0, (n != n) ? float(shifted) : 0.0,
                     float(bits & 0xffu) / 255.0, isinf(p.a.z) ? float(uint(p.i.y) >> 28) : 0.0);
}
