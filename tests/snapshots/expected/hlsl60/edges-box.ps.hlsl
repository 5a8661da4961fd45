cbuffer CrtParams : register(b0, space0)
{
    float2 crt_outputSize : packoffset(c0);
    float crt_time : packoffset(c0.z);
    float crt_shapeScale : packoffset(c0.w);
    float crt_pulseDepth : packoffset(c1);
    float crt_pulseRate : packoffset(c1.y);
};

Texture2D<float4> source : register(t1, space0);
SamplerState _source_sampler : register(s1, space0);

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
    float2 d = abs((vTexCoord * 2.0f) - 1.0f.xx) * crt_shapeScale;
    float4 c = float4((source.Sample(_source_sampler, vTexCoord).xyz * (1.0f - min(max(1.5f - max(d.x, d.y), 0.8f), 0.2f))) * mad(crt_pulseDepth, sin(mad((vTexCoord * crt_outputSize).y, 0.025f, crt_time * crt_pulseRate)), 1.0f), 1.0f);
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
