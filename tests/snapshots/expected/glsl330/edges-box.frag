#version 330
#ifdef GL_ARB_shading_language_420pack
#extension GL_ARB_shading_language_420pack : require
#endif

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    float time;
    float shapeScale;
    float pulseDepth;
    float pulseRate;
} crt;

layout(binding = 1) uniform sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 _166 = abs((vTexCoord * 2.0) - vec2(1.0)) * crt.shapeScale;
    vec4 _153 = vec4((texture(source, vTexCoord).xyz * (1.0 - clamp(1.5 - max(_166.x, _166.y), 0.8, 0.2))) * (crt.pulseDepth * sin((vTexCoord * crt.outputSize).y * 0.025 + (crt.time * crt.pulseRate)) + 1.0), 1.0);
    vec4 _204 = clamp(_153, vec4(-65504.0), vec4(65504.0));
    bvec4 _206 = isnan(_153);
    fragColor = vec4(_206.x ? vec4(0.0).x : _204.x, _206.y ? vec4(0.0).y : _204.y, _206.z ? vec4(0.0).z : _204.z, _206.w ? vec4(0.0).w : _204.w);
}

