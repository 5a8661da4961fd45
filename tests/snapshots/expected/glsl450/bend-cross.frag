#version 450

vec4 _363;

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
    vec4 _234 = (vec4(vTexCoord.xyyx) * 2.0) - vec4(1.0);
    vec2 _238 = _234.xy;
    vec2 _246 = _234.zw * fma(crt.bendAmount, dot(_238, _238), 1.0);
    vec4 _346;
    _346.z = _246.x;
    _346.w = _246.y;
    vec2 _253 = _346.wz * 0.5;
    vec2 _255 = _253 + vec2(0.5);
    vec4 _193 = texture(source, _255);
    vec4 _262 = texture(source, _253 + vec2(0.502499997615814208984375, 0.5));
    vec4 _267 = texture(source, _253 + vec2(0.497500002384185791015625, 0.5));
    vec4 _274 = texture(source, _253 + vec2(0.5, 0.502499997615814208984375));
    vec4 _281 = texture(source, _253 + vec2(0.5, 0.497500002384185791015625));
    vec3 _353;
    do
    {
        float _298 = _255.x;
        bool _299 = _298 < 0.0;
        bool _306;
        if (!_299)
        {
            _306 = _298 > 1.0;
        }
        else
        {
            _306 = _299;
        }
        if (_306)
        {
            _353 = crt.edgeColor;
            break;
        }
        float _312 = _255.y;
        bool _313 = _312 < 0.0;
        bool _320;
        if (!_313)
        {
            _320 = _312 > 1.0;
        }
        else
        {
            _320 = _313;
        }
        if (_320)
        {
            _353 = crt.edgeColor.zyx;
            break;
        }
        _353 = mix(_193.xyz, (((_262.xyz + _267.xyz) + _274.xyz) + _281.xyz) * 0.25, vec3(crt.tapMix));
        break;
    } while(false);
    fragColor = vec4(_353, 1.0);
}

