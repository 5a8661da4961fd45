static float4 undefined;

cbuffer CrtParams : register(b0)
{
    float2 crt_outputSize : packoffset(c0);
    float crt_time : packoffset(c0.z);
    float crt_bendAmount : packoffset(c0.w);
    float3 crt_edgeColor : packoffset(c1);
    float crt_tapMix : packoffset(c1.w);
    int crt_loopCount : packoffset(c2);
    int crt_bandWidth : packoffset(c2.y);
    float crt_pickDim : packoffset(c2.z);
    float crt_shapeScale : packoffset(c2.w);
    float crt_pulseDepth : packoffset(c3);
    float crt_pulseRate : packoffset(c3.y);
};

Texture2D<float4> source : register(t1);
SamplerState _source_sampler : register(s1);

static float2 vTexCoord;
static float4 fragColor;

struct SPIRV_Cross_Input
{
    float2 vTexCoord : TEXCOORD0;
};

struct SPIRV_Cross_Output
{
    float4 fragColor : SV_Target0;
};

float mod(float x, float y)
{
    return x - y * floor(x / y);
}

float2 mod(float2 x, float2 y)
{
    return x - y * floor(x / y);
}

float3 mod(float3 x, float3 y)
{
    return x - y * floor(x / y);
}

float4 mod(float4 x, float4 y)
{
    return x - y * floor(x / y);
}

void frag_main()
{
    float2 product = vTexCoord * crt_outputSize;
    float4 q = (float4(vTexCoord.xyyx) * 2.0f) - 1.0f.xxxx;
    float2 q_xy = q.xy;
    float2 product_1 = q.zw * mad(crt_bendAmount, dot(q_xy, q_xy), 1.0f);
    float4 q_1;
    q_1.z = product_1.x;
    q_1.w = product_1.y;
    float2 sampleUv = (q_1.wz * 0.5f) + 0.5f.xx;
    float sampleUv_x = sampleUv.x;
    float sampleUv_y = sampleUv.y;
    float3 color_1 = lerp(source.Sample(_source_sampler, sampleUv).xyz, source.Sample(_source_sampler, sampleUv + (float2(ddx(sampleUv_x), ddy(sampleUv_y)) * 4.0f)).xyz, (crt_tapMix * clamp(length(fwidth(sampleUv)) * 100.0f, 0.0f, 1.0f)).xxx);
    float color_y = color_1.y;
    float4 s;
    s = float4(color_1.x, color_y, color_1.z, 1.0f);
    int k_1;
    float4 s_1;
    int k = 0;
    for (;;)
    {
        s_1 = s;
        s_1.y = mad(color_y, 0.5f, 0.01f * float(k));
        k_1 = k + 1;
        if (k_1 >= crt_loopCount)
        {
            break;
        }
        s = s_1;
        k = k_1;
        continue;
    }
    int x = int(product.x) - 10;
    float part = product.y;
    float3 color_2 = (s_1.xyz * s.w) * mad(0.03f, mod(part - 4.0f, -5.0f), mad(-0.001f, float(x / (-3)), mad(0.01f, float(x % crt_bandWidth), mad(0.02f, float(x / crt_bandWidth), 1.0f))));
    float3 tint;
    switch (int(part) & 3)
    {
        case 0:
        {
            tint = float3(1.0f, crt_pickDim, crt_pickDim);
            break;
        }
        case 1:
        case 2:
        {
            tint = float3(crt_pickDim, 1.0f, crt_pickDim);
            break;
        }
        default:
        {
            tint = float3(crt_pickDim, crt_pickDim, 1.0f);
            break;
        }
    }
    float lift;
    if (sampleUv_x > 0.5f)
    {
        lift = sqrt(max(color_2.y, 0.0f));
    }
    else
    {
        float color_y_1 = color_2.y;
        lift = color_y_1 * color_y_1;
    }
    float2 d = abs((sampleUv * 2.0f) - 1.0f.xx) * crt_shapeScale;
    float3 color;
    do
    {
        bool cond_2 = sampleUv_x < 0.0f;
        bool cond;
        if (!cond_2)
        {
            cond = sampleUv_x > 1.0f;
        }
        else
        {
            cond = cond_2;
        }
        if (cond)
        {
            color = crt_edgeColor;
            break;
        }
        bool cond_3 = sampleUv_y < 0.0f;
        bool cond_1;
        if (!cond_3)
        {
            cond_1 = sampleUv_y > 1.0f;
        }
        else
        {
            cond_1 = cond_3;
        }
        if (cond_1)
        {
            color = crt_edgeColor.zyx;
            break;
        }
        color = (mad(color_2, tint, (((vTexCoord.y < 0.5f) ? 0.01f : (-0.01f)) * lift).xxx) * min(max(1.5f - max(d.x, d.y), 0.8f), 0.2f)) * mad(crt_pulseDepth, sin(mad(part, 0.025f, crt_time * crt_pulseRate)), 1.0f);
        break;
    } while(false);
    float4 c = float4(color, 1.0f);
    float4 clamped = clamp(c, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 cond_4 = isnan(c);
    fragColor = float4(cond_4.x ? 0.0f : clamped.x, cond_4.y ? 0.0f : clamped.y, cond_4.z ? 0.0f : clamped.z, cond_4.w ? 0.0f : clamped.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
