static float4 _393;

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
    float4 _253 = (float4(vTexCoord.xyyx) * 2.0f) - 1.0f.xxxx;
    float2 _257 = _253.xy;
    float2 _265 = _253.zw * mad(crt_bendAmount, dot(_257, _257), 1.0f);
    float4 _374;
    _374.z = _265.x;
    _374.w = _265.y;
    float2 _272 = _374.wz * 0.5f;
    float2 _274 = _272 + 0.5f.xx;
    float4 _210 = source.Sample(_source_sampler, _274);
    float4 _281 = source.Sample(_source_sampler, _272 + float2(0.5025f, 0.5f));
    float4 _286 = source.Sample(_source_sampler, _272 + float2(0.4975f, 0.5f));
    float4 _293 = source.Sample(_source_sampler, _272 + float2(0.5f, 0.5025f));
    float4 _300 = source.Sample(_source_sampler, _272 + float2(0.5f, 0.4975f));
    float3 _381;
    do
    {
        float _317 = _274.x;
        bool _318 = _317 < 0.0f;
        bool _325;
        if (!_318)
        {
            _325 = _317 > 1.0f;
        }
        else
        {
            _325 = _318;
        }
        if (_325)
        {
            _381 = crt_edgeColor;
            break;
        }
        float _331 = _274.y;
        bool _332 = _331 < 0.0f;
        bool _339;
        if (!_332)
        {
            _339 = _331 > 1.0f;
        }
        else
        {
            _339 = _332;
        }
        if (_339)
        {
            _381 = crt_edgeColor.zyx;
            break;
        }
        _381 = lerp(_210.xyz, (((_281.xyz + _286.xyz) + _293.xyz) + _300.xyz) * 0.25f, crt_tapMix.xxx);
        break;
    } while(false);
    float4 _228 = float4(_381, 1.0f);
    float4 _353 = clamp(_228, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 _355 = isnan(_228);
    fragColor = float4(_355.x ? 0.0f.xxxx.x : _353.x, _355.y ? 0.0f.xxxx.y : _353.y, _355.z ? 0.0f.xxxx.z : _353.z, _355.w ? 0.0f.xxxx.w : _353.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
