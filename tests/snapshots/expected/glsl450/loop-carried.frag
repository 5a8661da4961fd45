#version 450

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    float tapMix;
    int loopCount;
} crt;

layout(binding = 1) uniform sampler2D source;

layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 texel = texture(source, vTexCoord);
    float value = dFdx(vTexCoord.x);
    float value_1 = dFdy(vTexCoord.y);
    vec2 value_2 = fwidth(vTexCoord);
    vec4 texel_1 = texture(source, vTexCoord + (vec2(value, value_1) * 4.0));
    vec3 color = mix(texel.xyz, texel_1.xyz, vec3(crt.tapMix * clamp(length(value_2) * 100.0, 0.0, 1.0)));
    float sum_2;
    float sum_1;
    int k = 0;
    float sum = 0.0;
    for (;;)
    {
        if (k < crt.loopCount)
        {
            if (k == 1)
            {
                sum_1 = sum;
                int k_1 = k + 1;
                sum = sum_1;
                k = k_1;
                continue;
            }
            float sum_3 = fma(color.x * float(k), 0.25, sum);
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
    vec4 c = vec4(color * fma(0.1, sum_2, 1.0), 1.0);
    fragColor = mix(clamp(c, vec4(-65504.0), vec4(65504.0)), vec4(0.0), isnan(c));
}

