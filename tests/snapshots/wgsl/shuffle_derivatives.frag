#version 450
// Covers: vector shuffles, composite construct/extract/insert and dFdx, dFdy, fwidth
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    vec4 t = texture(source, vTexCoord);
    vec2 d = vec2(dFdx(vTexCoord.x), dFdy(vTexCoord.y)) * 16.0;
    vec4 s = t.wzyx;
    s.y = d.x;
    s.z = fwidth(vTexCoord.y);
    mat2 m = mat2(s.xy, t.zw);
    fragColor = vec4(s.xy, m[1].x, t.x + d.y);
}
