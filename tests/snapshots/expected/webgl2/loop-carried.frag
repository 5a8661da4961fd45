#version 300 es
precision highp float;
precision highp int;

uniform vec2 outputSize;
uniform float tapMix;
uniform int loopCount;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 texel = texture(source, vTexCoord);
    float _498 = dFdx(vTexCoord.x);
    float _501 = dFdy(vTexCoord.y);
    vec2 _506 = fwidth(vTexCoord);
    vec4 texel_1 = texture(source, vTexCoord + (vec2(_498, _501) * 4.0));
    vec3 color = mix(texel.xyz, texel_1.xyz, vec3(tapMix * clamp(length(_506) * 100.0, 0.0, 1.0)));
    float sum_2;
    float sum_1;
    int k = 0;
    float sum = 0.0;
    for (;;)
    {
        if (k < loopCount)
        {
            if (k == 1)
            {
                sum_1 = sum;
                int k_1 = k + 1;
                sum = sum_1;
                k = k_1;
                continue;
            }
            float sum_3 = (color.x * float(k)) * 0.25 + sum;
            if (sum_3 > 2.0)
            {
                sum_2 = sum_3;
                break;
            }
            sum_1 = sum_3;
            int k_1_1 = k + 1;
            sum = sum_1;
            k = k_1_1;
            continue;
        }
        else
        {
            sum_2 = sum;
            break;
        }
    }
    vec4 c = vec4(color * (0.1 * sum_2 + 1.0), 1.0);
    vec4 _650 = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    fragColor = vec4(cond.x ? 0.0 : _650.x, cond.y ? 0.0 : _650.y, cond.z ? 0.0 : _650.z, cond.w ? 0.0 : _650.w);
}

