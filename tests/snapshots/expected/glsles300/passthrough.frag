#version 300 es
precision highp float;
precision highp int;

uniform highp sampler2D source;

layout(location = 0) out vec4 fragColor;
in vec2 vTexCoord;

void main()
{
    vec4 c = texture(source, vTexCoord);
    vec4 _122 = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    fragColor = vec4(cond.x ? vec4(0.0).x : _122.x, cond.y ? vec4(0.0).y : _122.y, cond.z ? vec4(0.0).z : _122.z, cond.w ? vec4(0.0).w : _122.w);
}

