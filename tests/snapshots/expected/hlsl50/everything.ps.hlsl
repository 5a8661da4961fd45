static float4 _842;

cbuffer CrtParams : register(b0)
{
    float2 crt_outputSize : packoffset(c0);
    float crt_time : packoffset(c0.z);
    float crt_bendAmount : packoffset(c0.w);
    float3 crt_edgeColor : packoffset(c1);
    float crt_tapMix : packoffset(c1.w);
    int crt_loopCount : packoffset(c2);
    int crt_bandWidth : packoffset(c2.y);
    float crt_pickDim : packoffset(c2.z);
    float crt_shapeScale : packoffset(c2.w);
    float crt_pulseDepth : packoffset(c3);
    float crt_pulseRate : packoffset(c3.y);
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

float mod(float x, float y)
{
    return x - y * floor(x / y);
}

float2 mod(float2 x, float2 y)
{
    return x - y * floor(x / y);
}

float3 mod(float3 x, float3 y)
{
    return x - y * floor(x / y);
}

float4 mod(float4 x, float4 y)
{
    return x - y * floor(x / y);
}

void frag_main()
{
    float2 _402 = vTexCoord * crt_outputSize;
    float4 _490 = (float4(vTexCoord.xyyx) * 2.0f) - 1.0f.xxxx;
    float2 _494 = _490.xy;
    float2 _502 = _490.zw * mad(crt_bendAmount, dot(_494, _494), 1.0f);
    float4 _804;
    _804.z = _502.x;
    _804.w = _502.y;
    float2 _511 = (_804.wz * 0.5f) + 0.5f.xx;
    float _517 = _511.x;
    float _520 = _511.y;
    float3 _541 = lerp(source.Sample(_source_sampler, _511).xyz, source.Sample(_source_sampler, _511 + (float2(ddx(_517), ddy(_520)) * 4.0f)).xyz, (crt_tapMix * clamp(length(fwidth(_511)) * 100.0f, 0.0f, 1.0f)).xxx);
    float _548 = _541.y;
    float4 _829;
    _829 = float4(_541.x, _548, _541.z, 1.0f);
    int _563;
    float4 _811;
    int _828 = 0;
    for (;;)
    {
        _811 = _829;
        _811.y = mad(_548, 0.5f, 0.01f * float(_828));
        _563 = _828 + 1;
        if (_563 >= crt_loopCount)
        {
            break;
        }
        _829 = _811;
        _828 = _563;
        continue;
    }
    int _587 = int(_402.x) - 10;
    float _599 = _402.y;
    float3 _618 = (_811.xyz * _829.w) * mad(0.03f, mod(_599 - 4.0f, -5.0f), mad(-0.001f, float(_587 / (-3)), mad(0.01f, float(_587 % crt_bandWidth), mad(0.02f, float(_587 / crt_bandWidth), 1.0f))));
    float3 _832;
    switch (int(_599) & 3)
    {
        case 0:
        {
            _832 = float3(1.0f, crt_pickDim, crt_pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _832 = float3(crt_pickDim, 1.0f, crt_pickDim);
            break;
        }
        default:
        {
            _832 = float3(crt_pickDim, crt_pickDim, 1.0f);
            break;
        }
    }
    float _830;
    if (_517 > 0.5f)
    {
        _830 = sqrt(max(_618.y, 0.0f));
    }
    else
    {
        float _652 = _618.y;
        _830 = _652 * _652;
    }
    float2 _683 = abs((_511 * 2.0f) - 1.0f.xx) * crt_shapeScale;
    float3 _833;
    do
    {
        bool _720 = _517 < 0.0f;
        bool _727;
        if (!_720)
        {
            _727 = _517 > 1.0f;
        }
        else
        {
            _727 = _720;
        }
        if (_727)
        {
            _833 = crt_edgeColor;
            break;
        }
        bool _734 = _520 < 0.0f;
        bool _741;
        if (!_734)
        {
            _741 = _520 > 1.0f;
        }
        else
        {
            _741 = _734;
        }
        if (_741)
        {
            _833 = crt_edgeColor.zyx;
            break;
        }
        _833 = (mad(_618, _832, (((vTexCoord.y < 0.5f) ? 0.01f : (-0.01f)) * _830).xxx) * clamp(1.5f - max(_683.x, _683.y), 0.8f, 0.2f)) * mad(crt_pulseDepth, sin(mad(_599, 0.025f, crt_time * crt_pulseRate)), 1.0f);
        break;
    } while(false);
    float4 _466 = float4(_833, 1.0f);
    float4 _755 = clamp(_466, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 _757 = isnan(_466);
    fragColor = float4(_757.x ? 0.0f.xxxx.x : _755.x, _757.y ? 0.0f.xxxx.y : _755.y, _757.z ? 0.0f.xxxx.z : _755.z, _757.w ? 0.0f.xxxx.w : _755.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
