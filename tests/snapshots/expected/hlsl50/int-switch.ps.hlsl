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
    float2 _179 = vTexCoord * crt_outputSize;
    float4 _200 = source.Sample(_source_sampler, vTexCoord);
    int _233 = int(_179.x) - 12;
    float _245 = _179.y;
    float3 _264 = _200.xyz * mad(0.03f, mod(_245 - 4.0f, -6.0f), mad(-0.001f, float(_233 / (-3)), mad(0.01f, float(_233 % crt_bandWidth), mad(0.02f, float(_233 / crt_bandWidth), 1.0f))));
    float3 _362;
    switch (int(_245) & 3)
    {
        case 0:
        {
            _362 = float3(1.0f, crt_pickDim, crt_pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _362 = float3(crt_pickDim, 1.0f, crt_pickDim);
            break;
        }
        default:
        {
            _362 = float3(crt_pickDim, crt_pickDim, 1.0f);
            break;
        }
    }
    float _360;
    if (vTexCoord.x > 0.5f)
    {
        _360 = sqrt(max(_264.y, 0.0f));
    }
    else
    {
        float _303 = _264.y;
        _360 = _303 * _303;
    }
    float4 _218 = float4(mad(_264, _362, (((vTexCoord.y < 0.5f) ? 0.01f : (-0.01f)) * _360).xxx), 1.0f);
    float4 _325 = clamp(_218, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 _327 = isnan(_218);
    fragColor = float4(_327.x ? 0.0f.xxxx.x : _325.x, _327.y ? 0.0f.xxxx.y : _325.y, _327.z ? 0.0f.xxxx.z : _325.z, _327.w ? 0.0f.xxxx.w : _325.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
