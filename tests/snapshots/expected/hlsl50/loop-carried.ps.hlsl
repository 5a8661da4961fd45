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
    float4 _162 = source.Sample(_source_sampler, vTexCoord);
    float _190 = ddx(vTexCoord.x);
    float _193 = ddy(vTexCoord.y);
    float2 _197 = fwidth(vTexCoord);
    float4 _206 = source.Sample(_source_sampler, vTexCoord + (float2(_190, _193) * 4.0f));
    float3 _213 = lerp(_162.xyz, _206.xyz, (crt_tapMix * clamp(length(_197) * 100.0f, 0.0f, 1.0f)).xxx);
    float _268;
    float _270;
    int _266 = 0;
    float _267 = 0.0f;
    for (;;)
    {
        if (_266 < crt_loopCount)
        {
            if (_266 == 1)
            {
                _270 = _267;
                int _243 = _266 + 1;
                _267 = _270;
                _266 = _243;
                continue;
            }
            float _236 = mad(_213.x * float(_266), 0.25f, _267);
            if (_236 > 2.0f)
            {
                _268 = _236;
                break;
            }
            _270 = _236;
            int _243 = _266 + 1;
            _267 = _270;
            _266 = _243;
            continue;
        }
        else
        {
            _268 = _267;
            break;
        }
    }
    float4 _180 = float4(_213 * mad(0.1f, _268, 1.0f), 1.0f);
    float4 _255 = clamp(_180, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 _257 = isnan(_180);
    fragColor = float4(_257.x ? 0.0f.xxxx.x : _255.x, _257.y ? 0.0f.xxxx.y : _255.y, _257.z ? 0.0f.xxxx.z : _255.z, _257.w ? 0.0f.xxxx.w : _255.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
