#version 450
// Covers: ternaries: plain selects of scalars and vectors, and one around a call that must stay a branch
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

float expensive(float x) { return sin(x) * 0.5; }
void main() {
    bool right = vTexCoord.x > p.a.x;
    float f = float(right);
    vec3 c = right ? vec3(0.25) : texture(source, vTexCoord).rgb;
    float g = vTexCoord.y > 0.5 ? expensive(vTexCoord.x) : 0.0;
    fragColor = vec4(f, c.g, g, right ? 1.0 : 0.5);
}
