cbuffer CrtParams : register(b0)
{
    float2 crt_outputSize : packoffset(c0);
    float crt_tapMix : packoffset(c0.z);
    int crt_loopCount : packoffset(c0.w);
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
    float4 texel = source.Sample(_source_sampler, vTexCoord);
    float value = ddx(vTexCoord.x);
    float value_1 = ddy(vTexCoord.y);
    float2 value_2 = fwidth(vTexCoord);
    float4 texel_1 = source.Sample(_source_sampler, vTexCoord + (float2(value, value_1) * 4.0f));
    float3 color = lerp(texel.xyz, texel_1.xyz, (crt_tapMix * clamp(length(value_2) * 100.0f, 0.0f, 1.0f)).xxx);
    float sum_2;
    float sum_1;
    int k = 0;
    float sum = 0.0f;
    for (;;)
    {
        if (k < crt_loopCount)
        {
            if (k == 1)
            {
                sum_1 = sum;
                int k_1 = k + 1;
                sum = sum_1;
                k = k_1;
                continue;
            }
            float sum_3 = mad(color.x * float(k), 0.25f, sum);
            if (sum_3 > 2.0f)
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
    float4 c = float4(color * mad(0.1f, sum_2, 1.0f), 1.0f);
    float4 clamped = clamp(c, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 cond = isnan(c);
    fragColor = float4(cond.x ? 0.0f : clamped.x, cond.y ? 0.0f : clamped.y, cond.z ? 0.0f : clamped.z, cond.w ? 0.0f : clamped.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
