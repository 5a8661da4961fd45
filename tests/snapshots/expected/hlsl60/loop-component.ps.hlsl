cbuffer CrtParams : register(b0, space0)
{
    float2 crt_outputSize : packoffset(c0);
    int crt_loopCount : packoffset(c0.z);
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
    float4 _105 = source.Sample(_source_sampler, vTexCoord);
    float _126 = _105.y;
    float4 _164;
    _164 = float4(_105.x, _126, _105.z, 1.0f);
    int _141;
    float4 _161;
    int _163 = 0;
    for (;;)
    {
        _161 = _164;
        _161.y = mad(_126, 0.89999997615814208984375f, 0.00999999977648258209228515625f * float(_163));
        _141 = _163 + 1;
        if (_141 >= crt_loopCount)
        {
            break;
        }
        _164 = _161;
        _163 = _141;
        continue;
    }
    fragColor = float4(_161.xyz * _164.w, 1.0f);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
