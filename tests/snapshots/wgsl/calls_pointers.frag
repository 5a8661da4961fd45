#version 450
// Covers: function calls with an inout parameter, and locals indexed in a loop (pointers when unoptimised)
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;
layout(set = 0, binding = 1) uniform sampler2D source;

void scale(inout vec3 c, float k) { c *= k; }
float twice(float x) { return x * 2.0; }
void main() {
    vec3 c = texture(source, vTexCoord).rgb;
    scale(c, twice(p.a.x) / 6.0);
    for (int k = 0; k < 3; ++k) c[k] = c[k] + 0.125;
    fragColor = vec4(c, 1.0);
}
