static float4 _1032;

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
    float4 q = (float4(vTexCoord.xyyx) * 2.0f) - 1.0f.xxxx;
    float2 _605 = q.xy;
    float2 _613 = q.zw * mad(crt_bendAmount, dot(_605, _605), 1.0f);
    float4 q_1;
    q_1.z = _613.x;
    q_1.w = _613.y;
    float2 _620 = q_1.wz * 0.5f;
    float2 sampleUv = _620 + 0.5f.xx;
    float4 texel = source.Sample(_source_sampler, sampleUv);
    float4 texel_1 = source.Sample(_source_sampler, _620 + float2(0.5025f, 0.5f));
    float4 texel_2 = source.Sample(_source_sampler, _620 + float2(0.4975f, 0.5f));
    float4 texel_3 = source.Sample(_source_sampler, _620 + float2(0.5f, 0.5025f));
    float4 texel_4 = source.Sample(_source_sampler, _620 + float2(0.5f, 0.4975f));
    float3 color;
    do
    {
        float _755 = sampleUv.x;
        bool _756 = _755 < 0.0f;
        bool _763;
        if (!_756)
        {
            _763 = _755 > 1.0f;
        }
        else
        {
            _763 = _756;
        }
        if (_763)
        {
            color = crt_edgeColor;
            break;
        }
        float _769 = sampleUv.y;
        bool _770 = _769 < 0.0f;
        bool _777;
        if (!_770)
        {
            _777 = _769 > 1.0f;
        }
        else
        {
            _777 = _770;
        }
        if (_777)
        {
            color = crt_edgeColor.zyx;
            break;
        }
        color = lerp(texel.xyz, (((texel_1.xyz + texel_2.xyz) + texel_3.xyz) + texel_4.xyz) * 0.25f, crt_tapMix.xxx);
        break;
    } while(false);
    float4 c = float4(color, 1.0f);
    float4 _825 = clamp(c, (-65504.0f).xxxx, 65504.0f.xxxx);
    bool4 _827 = isnan(c);
    fragColor = float4(_827.x ? 0.0f.xxxx.x : _825.x, _827.y ? 0.0f.xxxx.y : _825.y, _827.z ? 0.0f.xxxx.z : _825.z, _827.w ? 0.0f.xxxx.w : _825.w);
}

SPIRV_Cross_Output main(SPIRV_Cross_Input stage_input)
{
    vTexCoord = stage_input.vTexCoord;
    frag_main();
    SPIRV_Cross_Output stage_output;
    stage_output.fragColor = fragColor;
    return stage_output;
}
