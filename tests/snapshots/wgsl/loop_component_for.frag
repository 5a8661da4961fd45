#version 450
// Covers: a vector modified by component inside a for loop (exit at the header) and read after the loop
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    vec4 s = texture(source, vTexCoord);
    for (int k = 0; k < p.i.x; ++k) {
        s.y = s.y * p.a.x + float(k);
        s.w += 0.5;
    }
    fragColor = s;
}
