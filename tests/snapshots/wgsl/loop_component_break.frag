#version 450
// Covers: a vector built by component assignment inside a loop that exits by a break and is read after the loop
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    vec4 s = vec4(0);
    int k = 0;
    while (true) {
        s.y = float(k) * p.a.x;
        k++;
        if (k > p.i.x) break;
    }
    fragColor = s;
}
