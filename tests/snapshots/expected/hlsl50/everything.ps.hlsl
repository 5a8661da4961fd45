static float4 _812;

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
    float2 _385 = vTexCoord * crt_outputSize;
    float4 _471 = (float4(vTexCoord.xyyx) * 2.0f) - 1.0f.xxxx;
    float2 _475 = _471.xy;
    float2 _483 = _471.zw * mad(crt_bendAmount, dot(_475, _475), 1.0f);
    float4 _776;
    _776.z = _483.x;
    _776.w = _483.y;
    float2 _492 = (_776.wz * 0.5f) + 0.5f.xx;
    float _498 = _492.x;
    float _501 = _492.y;
    float3 _522 = lerp(source.Sample(_source_sampler, _492).xyz, source.Sample(_source_sampler, _492 + (float2(ddx(_498), ddy(_501)) * 4.0f)).xyz, (crt_tapMix * clamp(length(fwidth(_492)) * 100.0f, 0.0f, 1.0f)).xxx);
    float _529 = _522.y;
    float4 _801;
    _801 = float4(_522.x, _529, _522.z, 1.0f);
    int _544;
    float4 _783;
    int _800 = 0;
    for (;;)
    {
        _783 = _801;
        _783.y = mad(_529, 0.5f, 0.00999999977648258209228515625f * float(_800));
        _544 = _800 + 1;
        if (_544 >= crt_loopCount)
        {
            break;
        }
        _801 = _783;
        _800 = _544;
        continue;
    }
    int _568 = int(_385.x) - 10;
    float _580 = _385.y;
    float3 _599 = (_783.xyz * _801.w) * mad(0.02999999932944774627685546875f, mod(_580 - 4.0f, -5.0f), mad(-0.001000000047497451305389404296875f, float(_568 / (-3)), mad(0.00999999977648258209228515625f, float(_568 % crt_bandWidth), mad(0.0199999995529651641845703125f, float(_568 / crt_bandWidth), 1.0f))));
    float3 _804;
    switch (int(_580) & 3)
    {
        case 0:
        {
            _804 = float3(1.0f, crt_pickDim, crt_pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _804 = float3(crt_pickDim, 1.0f, crt_pickDim);
            break;
        }
        default:
        {
            _804 = float3(crt_pickDim, crt_pickDim, 1.0f);
            break;
        }
    }
    float _802;
    if (_498 > 0.5f)
    {
        _802 = sqrt(max(_599.y, 0.0f));
    }
    else
    {
        float _633 = _599.y;
        _802 = _633 * _633;
    }
    float2 _664 = abs((_492 * 2.0f) - 1.0f.xx) * crt_shapeScale;
    float3 _805;
    do
    {
        bool _701 = _498 < 0.0f;
        bool _708;
        if (!_701)
        {
            _708 = _498 > 1.0f;
        }
        else
        {
            _708 = _701;
        }
        if (_708)
        {
            _805 = crt_edgeColor;
            break;
        }
        bool _715 = _501 < 0.0f;
        bool _722;
        if (!_715)
        {
            _722 = _501 > 1.0f;
        }
        else
        {
            _722 = _715;
        }
        if (_722)
        {
            _805 = crt_edgeColor.zyx;
            break;
        }
        _805 = (mad(_599, _804, (((vTexCoord.y < 0.5f) ? 0.00999999977648258209228515625f : (-0.00999999977648258209228515625f)) * _802).xxx) * clamp(1.5f - max(_664.x, _664.y), 0.800000011920928955078125f, 0.20000000298023223876953125f)) * mad(crt_pulseDepth, sin(mad(_580, 0.02500000037252902984619140625f, crt_time * crt_pulseRate)), 1.0f);
        break;
    } while(false);
    fragColor = float4(_805, 1.0f);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
