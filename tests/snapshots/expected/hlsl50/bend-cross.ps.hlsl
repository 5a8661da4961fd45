static float4 undefined;

cbuffer CrtParams : register(b0)
{
    float2 crt_outputSize : packoffset(c0);
    float crt_bendAmount : packoffset(c0.z);
    float3 crt_edgeColor : packoffset(c1);
    float crt_tapMix : packoffset(c1.w);
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

void frag_main()
{
    float4 q = (float4(vTexCoord.xyyx) * 2.0f) - 1.0f.xxxx;
    float2 q_xy = q.xy;
    float2 product = q.zw * mad(crt_bendAmount, dot(q_xy, q_xy), 1.0f);
    float4 q_1;
    q_1.z = product.x;
    q_1.w = product.y;
    float2 product_1 = q_1.wz * 0.5f;
    float2 sampleUv = product_1 + 0.5f.xx;
    float4 texel = source.Sample(_source_sampler, sampleUv);
    float4 texel_1 = source.Sample(_source_sampler, product_1 + float2(0.5025f, 0.5f));
    float4 texel_2 = source.Sample(_source_sampler, product_1 + float2(0.4975f, 0.5f));
    float4 texel_3 = source.Sample(_source_sampler, product_1 + float2(0.5f, 0.5025f));
    float4 texel_4 = source.Sample(_source_sampler, product_1 + float2(0.5f, 0.4975f));
    float3 color;
    do
    {
        float sampleUv_x = sampleUv.x;
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
        float sampleUv_y = sampleUv.y;
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
        color = lerp(texel.xyz, (((texel_1.xyz + texel_2.xyz) + texel_3.xyz) + texel_4.xyz) * 0.25f, crt_tapMix.xxx);
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
