#version 450
// Covers: a for loop with continue and break, loop-carried float and int, and a do-while
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    float sum = 0.0;
    int last = -1;
    for (int k = 0; k < p.i.x; ++k) {
        if (k == p.i.y) continue;
        if (sum > p.a.x) break;
        sum += float(k) * vTexCoord.x * 2.0;
        last = k;
    }
    int w = 0;
    do { w += 2; } while (w < p.i.y);
    fragColor = vec4(sum, float(last), float(w), 1.0);
}
