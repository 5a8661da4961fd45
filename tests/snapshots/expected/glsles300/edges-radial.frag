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
    vec4 _145 = vec4((texture(source, vTexCoord).xyz * (1.0 - smoothstep(0.3, 0.9, length((vTexCoord * 2.0) - vec2(1.0)) * crt.shapeScale))) * (crt.pulseDepth * sin((vTexCoord * crt.outputSize).y * 0.025 + (crt.time * crt.pulseRate)) + 1.0), 1.0);
    vec4 _187 = clamp(_145, vec4(-65504.0), vec4(65504.0));
    bvec4 _189 = isnan(_145);
    fragColor = vec4(_189.x ? vec4(0.0).x : _187.x, _189.y ? vec4(0.0).y : _187.y, _189.z ? vec4(0.0).z : _187.z, _189.w ? vec4(0.0).w : _187.w);
}

