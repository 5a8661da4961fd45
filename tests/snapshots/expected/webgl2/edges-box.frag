#version 300 es
precision highp float;
precision highp int;

uniform vec2 outputSize;
uniform float time;
uniform float shapeScale;
uniform float pulseDepth;
uniform float pulseRate;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 d = abs((vTexCoord * 2.0) - vec2(1.0)) * shapeScale;
    vec4 c = vec4((texture(source, vTexCoord).xyz * (1.0 - min(max(1.5 - max(d.x, d.y), 0.8), 0.2))) * (pulseDepth * sin((vTexCoord * outputSize).y * 0.025 + (time * pulseRate)) + 1.0), 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    fragColor = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

