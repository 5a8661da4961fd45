#version 450
// Covers: an early return, a bezel-style branch and discard ending their paths before a texture read
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    if (vTexCoord.x < 0.25) { fragColor = vec4(1.0, 0.0, 0.0, 1.0); return; }
    if (vTexCoord.x > 0.75) discard;
    bool outside = any(bvec4(lessThan(vTexCoord, p.a.xy), greaterThan(vTexCoord, p.a.zw)));
    fragColor = outside ? p.b : texture(source, vTexCoord);
}
