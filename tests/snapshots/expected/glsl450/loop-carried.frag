#version 450

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    float tapMix;
    int loopCount;
} crt;

layout(binding = 1) uniform sampler2D source;

layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 _162 = texture(source, vTexCoord);
    float _190 = dFdx(vTexCoord.x);
    float _193 = dFdy(vTexCoord.y);
    vec2 _197 = fwidth(vTexCoord);
    vec4 _206 = texture(source, vTexCoord + (vec2(_190, _193) * 4.0));
    vec3 _213 = mix(_162.xyz, _206.xyz, vec3(crt.tapMix * clamp(length(_197) * 100.0, 0.0, 1.0)));
    float _268;
    float _270;
    int _266 = 0;
    float _267 = 0.0;
    for (;;)
    {
        if (_266 < crt.loopCount)
        {
            if (_266 == 1)
            {
                _270 = _267;
                int _243 = _266 + 1;
                _267 = _270;
                _266 = _243;
                continue;
            }
            float _236 = fma(_213.x * float(_266), 0.25, _267);
            if (_236 > 2.0)
            {
                _268 = _236;
                break;
            }
            _270 = _236;
            int _243 = _266 + 1;
            _267 = _270;
            _266 = _243;
            continue;
        }
        else
        {
            _268 = _267;
            break;
        }
    }
    vec4 _180 = vec4(_213 * fma(0.1, _268, 1.0), 1.0);
    fragColor = mix(clamp(_180, vec4(-65504.0), vec4(65504.0)), vec4(0.0), isnan(_180));
}

