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
    float2 product = vTexCoord * crt_outputSize;
    float4 texel = source.Sample(_source_sampler, vTexCoord);
    int x = int(product.x) - 12;
    float part = product.y;
    float3 color = texel.xyz * mad(0.03f, mod(part - 4.0f, -6.0f), mad(-0.001f, float(x / (-3)), mad(0.01f, float(x % crt_bandWidth), mad(0.02f, float(x / crt_bandWidth), 1.0f))));
    float3 tint;
    switch (int(part) & 3)
    {
        case 0:
        {
            tint = float3(1.0f, crt_pickDim, crt_pickDim);
            break;
        }
        case 1:
        case 2:
        {
            tint = float3(crt_pickDim, 1.0f, crt_pickDim);
            break;
        }
        default:
        {
            tint = float3(crt_pickDim, crt_pickDim, 1.0f);
            break;
        }
    }
    float lift;
    if (vTexCoord.x > 0.5f)
    {
        lift = sqrt(max(color.y, 0.0f));
    }
    else
    {
        float color_y = color.y;
        lift = color_y * color_y;
    }
    float4 c = float4(mad(color, tint, (((vTexCoord.y < 0.5f) ? 0.01f : (-0.01f)) * lift).xxx), 1.0f);
    float4 clamped = clamp(c, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 cond = isnan(c);
    fragColor = float4(cond.x ? 0.0f : clamped.x, cond.y ? 0.0f : clamped.y, cond.z ? 0.0f : clamped.z, cond.w ? 0.0f : clamped.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
