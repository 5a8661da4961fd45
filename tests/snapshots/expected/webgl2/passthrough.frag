#version 300 es
precision highp float;
precision highp int;

uniform highp sampler2D source;

layout(location = 0) out vec4 fragColor;
in vec2 vTexCoord;

void main()
{
    vec4 c = texture(source, vTexCoord);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    fragColor = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

