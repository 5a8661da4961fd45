#version 300 es
precision highp float;
precision highp int;

layout(std140) uniform CrtParams
{
    vec2 outputSize;
    float time;
    float shapeScale;
    float pulseDepth;
    float pulseRate;
} crt;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 c = vec4((texture(source, vTexCoord).xyz * (1.0 - smoothstep(0.3, 0.9, length((vTexCoord * 2.0) - vec2(1.0)) * crt.shapeScale))) * (crt.pulseDepth * sin((vTexCoord * crt.outputSize).y * 0.025 + (crt.time * crt.pulseRate)) + 1.0), 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    fragColor = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

