#version 300 es
precision highp float;
precision highp int;

layout(std140) uniform CrtParams
{
    vec2 outputSize;
    int loopCount;
} crt;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 texel = texture(source, vTexCoord);
    float texel_y = texel.y;
    vec4 s;
    s = vec4(texel.x, texel_y, texel.z, 1.0);
    int k_1;
    vec4 s_1;
    int k = 0;
    for (;;)
    {
        s_1 = s;
        s_1.y = texel_y * 0.9 + (0.01 * float(k));
        k_1 = k + 1;
        if (k_1 >= crt.loopCount)
        {
            break;
        }
        s = s_1;
        k = k_1;
        continue;
    }
    vec4 c = vec4(s_1.xyz * s.w, 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    fragColor = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

