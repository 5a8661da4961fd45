#version 450
// Covers: a switch on an int uniform with a fall-through label pair and default
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void main() {
    float v;
    switch (p.i.x) {
        case 0: v = 0.1; break;
        case 1: case 2: v = 0.2; break;
        case -3: v = vTexCoord.x; break;
        default: v = 0.3; break;
    }
    fragColor = vec4(v, vTexCoord, 1.0);
}
