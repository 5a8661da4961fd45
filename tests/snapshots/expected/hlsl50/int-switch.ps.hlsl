cbuffer CrtParams : register(b0)
{
    float2 crt_outputSize : packoffset(c0);
    int crt_bandWidth : packoffset(c0.z);
    float crt_pickDim : packoffset(c0.w);
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
    float2 _160 = vTexCoord * crt_outputSize;
    float4 _182 = source.Sample(_source_sampler, vTexCoord);
    int _213 = int(_160.x) - 12;
    float _225 = _160.y;
    float3 _244 = _182.xyz * mad(0.02999999932944774627685546875f, mod(_225 - 4.0f, -6.0f), mad(-0.001000000047497451305389404296875f, float(_213 / (-3)), mad(0.00999999977648258209228515625f, float(_213 % crt_bandWidth), mad(0.0199999995529651641845703125f, float(_213 / crt_bandWidth), 1.0f))));
    float3 _333;
    switch (int(_225) & 3)
    {
        case 0:
        {
            _333 = float3(1.0f, crt_pickDim, crt_pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _333 = float3(crt_pickDim, 1.0f, crt_pickDim);
            break;
        }
        default:
        {
            _333 = float3(crt_pickDim, crt_pickDim, 1.0f);
            break;
        }
    }
    float _331;
    if (vTexCoord.x > 0.5f)
    {
        _331 = sqrt(max(_244.y, 0.0f));
    }
    else
    {
        float _283 = _244.y;
        _331 = _283 * _283;
    }
    fragColor = float4(mad(_244, _333, (((vTexCoord.y < 0.5f) ? 0.00999999977648258209228515625f : (-0.00999999977648258209228515625f)) * _331).xxx), 1.0f);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
