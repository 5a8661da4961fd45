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
    vec4 _144 = vec4((texture(source, vTexCoord).xyz * smoothstep(0.89999997615814208984375, 0.300000011920928955078125, length((vTexCoord * 2.0) - vec2(1.0)) * crt.shapeScale)) * (crt.pulseDepth * sin((vTexCoord * crt.outputSize).y * 0.02500000037252902984619140625 + (crt.time * crt.pulseRate)) + 1.0), 1.0);
    vec4 _185 = clamp(_144, vec4(-65504.0), vec4(65504.0));
    bvec4 _187 = isnan(_144);
    fragColor = vec4(_187.x ? vec4(0.0).x : _185.x, _187.y ? vec4(0.0).y : _185.y, _187.z ? vec4(0.0).z : _185.z, _187.w ? vec4(0.0).w : _185.w);
}

