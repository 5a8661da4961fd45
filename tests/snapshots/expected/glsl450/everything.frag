#version 450

vec4 _812;

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    float time;
    float bendAmount;
    vec3 edgeColor;
    float tapMix;
    int loopCount;
    int bandWidth;
    float pickDim;
    float shapeScale;
    float pulseDepth;
    float pulseRate;
} crt;

layout(binding = 1) uniform sampler2D source;

layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 _385 = vTexCoord * crt.outputSize;
    vec4 _471 = (vec4(vTexCoord.xyyx) * 2.0) - vec4(1.0);
    vec2 _475 = _471.xy;
    vec2 _483 = _471.zw * fma(crt.bendAmount, dot(_475, _475), 1.0);
    vec4 _776;
    _776.z = _483.x;
    _776.w = _483.y;
    vec2 _492 = (_776.wz * 0.5) + vec2(0.5);
    float _498 = _492.x;
    float _501 = _492.y;
    vec3 _522 = mix(texture(source, _492).xyz, texture(source, _492 + (vec2(dFdx(_498), dFdy(_501)) * 4.0)).xyz, vec3(crt.tapMix * clamp(length(fwidth(_492)) * 100.0, 0.0, 1.0)));
    float _529 = _522.y;
    vec4 _801;
    _801 = vec4(_522.x, _529, _522.z, 1.0);
    int _544;
    vec4 _783;
    int _800 = 0;
    for (;;)
    {
        _783 = _801;
        _783.y = fma(_529, 0.5, 0.00999999977648258209228515625 * float(_800));
        _544 = _800 + 1;
        if (_544 >= crt.loopCount)
        {
            break;
        }
        _801 = _783;
        _800 = _544;
        continue;
    }
    int _568 = int(_385.x) - 10;
    float _580 = _385.y;
    vec3 _599 = (_783.xyz * _801.w) * fma(0.02999999932944774627685546875, mod(_580 - 4.0, -5.0), fma(-0.001000000047497451305389404296875, float(_568 / (-3)), fma(0.00999999977648258209228515625, float(_568 % crt.bandWidth), fma(0.0199999995529651641845703125, float(_568 / crt.bandWidth), 1.0))));
    vec3 _804;
    switch (int(_580) & 3)
    {
        case 0:
        {
            _804 = vec3(1.0, crt.pickDim, crt.pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _804 = vec3(crt.pickDim, 1.0, crt.pickDim);
            break;
        }
        default:
        {
            _804 = vec3(crt.pickDim, crt.pickDim, 1.0);
            break;
        }
    }
    float _802;
    if (_498 > 0.5)
    {
        _802 = sqrt(max(_599.y, 0.0));
    }
    else
    {
        float _633 = _599.y;
        _802 = _633 * _633;
    }
    vec2 _664 = abs((_492 * 2.0) - vec2(1.0)) * crt.shapeScale;
    vec3 _805;
    do
    {
        bool _701 = _498 < 0.0;
        bool _708;
        if (!_701)
        {
            _708 = _498 > 1.0;
        }
        else
        {
            _708 = _701;
        }
        if (_708)
        {
            _805 = crt.edgeColor;
            break;
        }
        bool _715 = _501 < 0.0;
        bool _722;
        if (!_715)
        {
            _722 = _501 > 1.0;
        }
        else
        {
            _722 = _715;
        }
        if (_722)
        {
            _805 = crt.edgeColor.zyx;
            break;
        }
        _805 = (fma(_599, _804, vec3(((vTexCoord.y < 0.5) ? 0.00999999977648258209228515625 : (-0.00999999977648258209228515625)) * _802)) * clamp(1.5 - max(_664.x, _664.y), 0.800000011920928955078125, 0.20000000298023223876953125)) * fma(crt.pulseDepth, sin(fma(_580, 0.02500000037252902984619140625, crt.time * crt.pulseRate)), 1.0);
        break;
    } while(false);
    fragColor = vec4(_805, 1.0);
}

