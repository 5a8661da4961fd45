cbuffer CrtParams : register(b0, space0)
{
    float2 crt_outputSize : packoffset(c0);
    float crt_tapMix : packoffset(c0.z);
    int crt_loopCount : packoffset(c0.w);
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
    float4 _144 = source.Sample(_source_sampler, vTexCoord);
    float _170 = ddx(vTexCoord.x);
    float _173 = ddy(vTexCoord.y);
    float2 _177 = fwidth(vTexCoord);
    float4 _186 = source.Sample(_source_sampler, vTexCoord + (float2(_170, _173) * 4.0f));
    float3 _193 = lerp(_144.xyz, _186.xyz, (crt_tapMix * clamp(length(_177) * 100.0f, 0.0f, 1.0f)).xxx);
    float _239;
    float _241;
    int _237 = 0;
    float _238 = 0.0f;
    for (;;)
    {
        if (_237 < crt_loopCount)
        {
            if (_237 == 1)
            {
                _241 = _238;
                int _223 = _237 + 1;
                _238 = _241;
                _237 = _223;
                continue;
            }
            float _216 = mad(_193.x * float(_237), 0.25f, _238);
            if (_216 > 2.0f)
            {
                _239 = _216;
                break;
            }
            _241 = _216;
            int _223 = _237 + 1;
            _238 = _241;
            _237 = _223;
            continue;
        }
        else
        {
            _239 = _238;
            break;
        }
    }
    fragColor = float4(_193 * mad(0.100000001490116119384765625f, _239, 1.0f), 1.0f);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
