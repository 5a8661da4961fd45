static float4 _363;

cbuffer CrtParams : register(b0, space0)
{
    float2 crt_outputSize : packoffset(c0);
    float crt_bendAmount : packoffset(c0.z);
    float3 crt_edgeColor : packoffset(c1);
    float crt_tapMix : packoffset(c1.w);
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
    float4 _234 = (float4(vTexCoord.xyyx) * 2.0f) - 1.0f.xxxx;
    float2 _238 = _234.xy;
    float2 _246 = _234.zw * mad(crt_bendAmount, dot(_238, _238), 1.0f);
    float4 _346;
    _346.z = _246.x;
    _346.w = _246.y;
    float2 _253 = _346.wz * 0.5f;
    float2 _255 = _253 + 0.5f.xx;
    float4 _193 = source.Sample(_source_sampler, _255);
    float4 _262 = source.Sample(_source_sampler, _253 + float2(0.502499997615814208984375f, 0.5f));
    float4 _267 = source.Sample(_source_sampler, _253 + float2(0.497500002384185791015625f, 0.5f));
    float4 _274 = source.Sample(_source_sampler, _253 + float2(0.5f, 0.502499997615814208984375f));
    float4 _281 = source.Sample(_source_sampler, _253 + float2(0.5f, 0.497500002384185791015625f));
    float3 _353;
    do
    {
        float _298 = _255.x;
        bool _299 = _298 < 0.0f;
        bool _306;
        if (!_299)
        {
            _306 = _298 > 1.0f;
        }
        else
        {
            _306 = _299;
        }
        if (_306)
        {
            _353 = crt_edgeColor;
            break;
        }
        float _312 = _255.y;
        bool _313 = _312 < 0.0f;
        bool _320;
        if (!_313)
        {
            _320 = _312 > 1.0f;
        }
        else
        {
            _320 = _313;
        }
        if (_320)
        {
            _353 = crt_edgeColor.zyx;
            break;
        }
        _353 = lerp(_193.xyz, (((_262.xyz + _267.xyz) + _274.xyz) + _281.xyz) * 0.25f, crt_tapMix.xxx);
        break;
    } while(false);
    fragColor = float4(_353, 1.0f);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
