#version 450

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    float time;
    float shapeScale;
    float pulseDepth;
    float pulseRate;
} crt;

layout(binding = 1) uniform sampler2D source;

layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 d = abs((vTexCoord * 2.0) - vec2(1.0)) * crt.shapeScale;
    vec4 c = vec4((texture(source, vTexCoord).xyz * (1.0 - min(max(1.5 - max(d.x, d.y), 0.8), 0.2))) * fma(crt.pulseDepth, sin(fma((vTexCoord * crt.outputSize).y, 0.025, crt.time * crt.pulseRate)), 1.0), 1.0);
    fragColor = mix(clamp(c, vec4(-65504.0), vec4(65504.0)), vec4(0.0), isnan(c));
}

