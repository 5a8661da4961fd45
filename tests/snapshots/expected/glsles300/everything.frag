#version 300 es
precision highp float;
precision highp int;

vec4 _842;

layout(std140) uniform CrtParams
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

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 _402 = vTexCoord * crt.outputSize;
    vec4 _490 = (vec4(vTexCoord.xyyx) * 2.0) - vec4(1.0);
    vec2 _494 = _490.xy;
    vec2 _502 = _490.zw * (crt.bendAmount * dot(_494, _494) + 1.0);
    vec4 _804;
    _804.z = _502.x;
    _804.w = _502.y;
    vec2 _511 = (_804.wz * 0.5) + vec2(0.5);
    float _517 = _511.x;
    float _520 = _511.y;
    vec3 _541 = mix(texture(source, _511).xyz, texture(source, _511 + (vec2(dFdx(_517), dFdy(_520)) * 4.0)).xyz, vec3(crt.tapMix * clamp(length(fwidth(_511)) * 100.0, 0.0, 1.0)));
    float _548 = _541.y;
    vec4 _829;
    _829 = vec4(_541.x, _548, _541.z, 1.0);
    int _563;
    vec4 _811;
    int _828 = 0;
    for (;;)
    {
        _811 = _829;
        _811.y = _548 * 0.5 + (0.01 * float(_828));
        _563 = _828 + 1;
        if (_563 >= crt.loopCount)
        {
            break;
        }
        _829 = _811;
        _828 = _563;
        continue;
    }
    int _587 = int(_402.x) - 10;
    float _599 = _402.y;
    vec3 _618 = (_811.xyz * _829.w) * (0.03 * mod(_599 - 4.0, -5.0) + ((-0.001) * float(_587 / (-3)) + (0.01 * float(_587 % crt.bandWidth) + (0.02 * float(_587 / crt.bandWidth) + 1.0))));
    vec3 _832;
    switch (int(_599) & 3)
    {
        case 0:
        {
            _832 = vec3(1.0, crt.pickDim, crt.pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _832 = vec3(crt.pickDim, 1.0, crt.pickDim);
            break;
        }
        default:
        {
            _832 = vec3(crt.pickDim, crt.pickDim, 1.0);
            break;
        }
    }
    float _830;
    if (_517 > 0.5)
    {
        _830 = sqrt(max(_618.y, 0.0));
    }
    else
    {
        float _652 = _618.y;
        _830 = _652 * _652;
    }
    vec2 _683 = abs((_511 * 2.0) - vec2(1.0)) * crt.shapeScale;
    vec3 _833;
    do
    {
        bool _720 = _517 < 0.0;
        bool _727;
        if (!_720)
        {
            _727 = _517 > 1.0;
        }
        else
        {
            _727 = _720;
        }
        if (_727)
        {
            _833 = crt.edgeColor;
            break;
        }
        bool _734 = _520 < 0.0;
        bool _741;
        if (!_734)
        {
            _741 = _520 > 1.0;
        }
        else
        {
            _741 = _734;
        }
        if (_741)
        {
            _833 = crt.edgeColor.zyx;
            break;
        }
        _833 = ((_618 * _832 + vec3(((vTexCoord.y < 0.5) ? 0.01 : (-0.01)) * _830)) * clamp(1.5 - max(_683.x, _683.y), 0.8, 0.2)) * (crt.pulseDepth * sin(_599 * 0.025 + (crt.time * crt.pulseRate)) + 1.0);
        break;
    } while(false);
    vec4 _466 = vec4(_833, 1.0);
    vec4 _755 = clamp(_466, vec4(-65504.0), vec4(65504.0));
    bvec4 _757 = isnan(_466);
    fragColor = vec4(_757.x ? vec4(0.0).x : _755.x, _757.y ? vec4(0.0).y : _755.y, _757.z ? vec4(0.0).z : _755.z, _757.w ? vec4(0.0).w : _755.w);
}

