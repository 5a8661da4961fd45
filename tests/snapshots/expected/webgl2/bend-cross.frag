#version 300 es
precision highp float;
precision highp int;

vec4 undefined;

uniform vec2 outputSize;
uniform float bendAmount;
uniform vec3 edgeColor;
uniform float tapMix;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 q = (vec4(vTexCoord.xyyx) * 2.0) - vec4(1.0);
    vec2 q_xy = q.xy;
    vec2 product = q.zw * (bendAmount * dot(q_xy, q_xy) + 1.0);
    vec4 q_1;
    q_1.z = product.x;
    q_1.w = product.y;
    vec2 product_1 = q_1.wz * 0.5;
    vec2 sampleUv = product_1 + vec2(0.5);
    vec4 texel = texture(source, sampleUv);
    vec4 texel_1 = texture(source, product_1 + vec2(0.5025, 0.5));
    vec4 texel_2 = texture(source, product_1 + vec2(0.4975, 0.5));
    vec4 texel_3 = texture(source, product_1 + vec2(0.5, 0.5025));
    vec4 texel_4 = texture(source, product_1 + vec2(0.5, 0.4975));
    vec3 color;
    do
    {
        float sampleUv_x = sampleUv.x;
        bool cond_2 = sampleUv_x < 0.0;
        bool cond;
        if (!cond_2)
        {
            cond = sampleUv_x > 1.0;
        }
        else
        {
            cond = cond_2;
        }
        if (cond)
        {
            color = edgeColor;
            break;
        }
        float sampleUv_y = sampleUv.y;
        bool cond_3 = sampleUv_y < 0.0;
        bool cond_1;
        if (!cond_3)
        {
            cond_1 = sampleUv_y > 1.0;
        }
        else
        {
            cond_1 = cond_3;
        }
        if (cond_1)
        {
            color = edgeColor.zyx;
            break;
        }
        color = mix(texel.xyz, (((texel_1.xyz + texel_2.xyz) + texel_3.xyz) + texel_4.xyz) * 0.25, vec3(tapMix));
        break;
    } while(false);
    vec4 c = vec4(color, 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond_4 = isnan(c);
    fragColor = vec4(cond_4.x ? 0.0 : clamped.x, cond_4.y ? 0.0 : clamped.y, cond_4.z ? 0.0 : clamped.z, cond_4.w ? 0.0 : clamped.w);
}

