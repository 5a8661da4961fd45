#version 300 es
precision highp float;
precision highp int;

vec4 undefined;

layout(std140) uniform CrtParams
{
    vec2 outputSize;
    float time;
    float bendAmount;
    vec3 edgeColor;
    float tapMix;
    int loopCount;
    int bandWidth;
    float pickDim;
    float shapeScale;
    float pulseDepth;
    float pulseRate;
} crt;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 product = vTexCoord * crt.outputSize;
    vec4 q = (vec4(vTexCoord.xyyx) * 2.0) - vec4(1.0);
    vec2 q_xy = q.xy;
    vec2 product_1 = q.zw * (crt.bendAmount * dot(q_xy, q_xy) + 1.0);
    vec4 q_1;
    q_1.z = product_1.x;
    q_1.w = product_1.y;
    vec2 sampleUv = (q_1.wz * 0.5) + vec2(0.5);
    float sampleUv_x = sampleUv.x;
    float sampleUv_y = sampleUv.y;
    vec3 color_1 = mix(texture(source, sampleUv).xyz, texture(source, sampleUv + (vec2(dFdx(sampleUv_x), dFdy(sampleUv_y)) * 4.0)).xyz, vec3(crt.tapMix * clamp(length(fwidth(sampleUv)) * 100.0, 0.0, 1.0)));
    float color_y = color_1.y;
    vec4 s;
    s = vec4(color_1.x, color_y, color_1.z, 1.0);
    int k_1;
    vec4 s_1;
    int k = 0;
    for (;;)
    {
        s_1 = s;
        s_1.y = color_y * 0.5 + (0.01 * float(k));
        k_1 = k + 1;
        if (k_1 >= crt.loopCount)
        {
            break;
        }
        s = s_1;
        k = k_1;
        continue;
    }
    int x = int(product.x) - 10;
    float part = product.y;
    vec3 color_2 = (s_1.xyz * s.w) * (0.03 * mod(part - 4.0, -5.0) + ((-0.001) * float(x / (-3)) + (0.01 * float(x % crt.bandWidth) + (0.02 * float(x / crt.bandWidth) + 1.0))));
    vec3 tint;
    switch (int(part) & 3)
    {
        case 0:
        {
            tint = vec3(1.0, crt.pickDim, crt.pickDim);
            break;
        }
        case 1:
        case 2:
        {
            tint = vec3(crt.pickDim, 1.0, crt.pickDim);
            break;
        }
        default:
        {
            tint = vec3(crt.pickDim, crt.pickDim, 1.0);
            break;
        }
    }
    float lift;
    if (sampleUv_x > 0.5)
    {
        lift = sqrt(max(color_2.y, 0.0));
    }
    else
    {
        float color_y_1 = color_2.y;
        lift = color_y_1 * color_y_1;
    }
    vec2 d = abs((sampleUv * 2.0) - vec2(1.0)) * crt.shapeScale;
    vec3 color;
    do
    {
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
            color = crt.edgeColor;
            break;
        }
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
            color = crt.edgeColor.zyx;
            break;
        }
        color = ((color_2 * tint + vec3(((vTexCoord.y < 0.5) ? 0.01 : (-0.01)) * lift)) * min(max(1.5 - max(d.x, d.y), 0.8), 0.2)) * (crt.pulseDepth * sin(part * 0.025 + (crt.time * crt.pulseRate)) + 1.0);
        break;
    } while(false);
    vec4 c = vec4(color, 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond_4 = isnan(c);
    fragColor = vec4(cond_4.x ? 0.0 : clamped.x, cond_4.y ? 0.0 : clamped.y, cond_4.z ? 0.0 : clamped.z, cond_4.w ? 0.0 : clamped.w);
}

