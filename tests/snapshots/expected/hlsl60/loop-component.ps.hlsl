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
    float4 _123 = source.Sample(_source_sampler, vTexCoord);
    float _146 = _123.y;
    float4 _193;
    _193 = float4(_123.x, _146, _123.z, 1.0f);
    int _161;
    float4 _190;
    int _192 = 0;
    for (;;)
    {
        _190 = _193;
        _190.y = mad(_146, 0.9f, 0.01f * float(_192));
        _161 = _192 + 1;
        if (_161 >= crt_loopCount)
        {
            break;
        }
        _193 = _190;
        _192 = _161;
        continue;
    }
    float4 _136 = float4(_190.xyz * _193.w, 1.0f);
    float4 _180 = clamp(_136, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 _182 = isnan(_136);
    fragColor = float4(_182.x ? 0.0f.xxxx.x : _180.x, _182.y ? 0.0f.xxxx.y : _180.y, _182.z ? 0.0f.xxxx.z : _180.z, _182.w ? 0.0f.xxxx.w : _180.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
