cbuffer CrtParams : register(b0)
{
    float2 crt_outputSize : packoffset(c0);
    int crt_loopCount : packoffset(c0.z);
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
    float texel_y = texel.y;
    float4 s;
    s = float4(texel.x, texel_y, texel.z, 1.0f);
    int k_1;
    float4 s_1;
    int k = 0;
    for (;;)
    {
        s_1 = s;
        s_1.y = mad(texel_y, 0.9f, 0.01f * float(k));
        k_1 = k + 1;
        if (k_1 >= crt_loopCount)
        {
            break;
        }
        s = s_1;
        k = k_1;
        continue;
    }
    float4 c = float4(s_1.xyz * s.w, 1.0f);
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
