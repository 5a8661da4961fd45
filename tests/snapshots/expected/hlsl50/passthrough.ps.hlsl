Texture2D<float4> source : register(t1);
SamplerState _source_sampler : register(s1);

static float4 fragColor;
static float2 vTexCoord;

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
    float4 c = source.Sample(_source_sampler, vTexCoord);
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
