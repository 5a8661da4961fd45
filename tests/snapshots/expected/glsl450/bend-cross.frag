#version 450

vec4 _393;

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    float bendAmount;
    vec3 edgeColor;
    float tapMix;
} crt;

layout(binding = 1) uniform sampler2D source;

layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 _253 = (vec4(vTexCoord.xyyx) * 2.0) - vec4(1.0);
    vec2 _257 = _253.xy;
    vec2 _265 = _253.zw * fma(crt.bendAmount, dot(_257, _257), 1.0);
    vec4 _374;
    _374.z = _265.x;
    _374.w = _265.y;
    vec2 _272 = _374.wz * 0.5;
    vec2 _274 = _272 + vec2(0.5);
    vec4 _210 = texture(source, _274);
    vec4 _281 = texture(source, _272 + vec2(0.5025, 0.5));
    vec4 _286 = texture(source, _272 + vec2(0.4975, 0.5));
    vec4 _293 = texture(source, _272 + vec2(0.5, 0.5025));
    vec4 _300 = texture(source, _272 + vec2(0.5, 0.4975));
    vec3 _381;
    do
    {
        float _317 = _274.x;
        bool _318 = _317 < 0.0;
        bool _325;
        if (!_318)
        {
            _325 = _317 > 1.0;
        }
        else
        {
            _325 = _318;
        }
        if (_325)
        {
            _381 = crt.edgeColor;
            break;
        }
        float _331 = _274.y;
        bool _332 = _331 < 0.0;
        bool _339;
        if (!_332)
        {
            _339 = _331 > 1.0;
        }
        else
        {
            _339 = _332;
        }
        if (_339)
        {
            _381 = crt.edgeColor.zyx;
            break;
        }
        _381 = mix(_210.xyz, (((_281.xyz + _286.xyz) + _293.xyz) + _300.xyz) * 0.25, vec3(crt.tapMix));
        break;
    } while(false);
    vec4 _228 = vec4(_381, 1.0);
    fragColor = mix(clamp(_228, vec4(-65504.0), vec4(65504.0)), vec4(0.0), isnan(_228));
}

