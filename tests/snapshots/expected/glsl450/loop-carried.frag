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
    vec4 _144 = texture(source, vTexCoord);
    float _170 = dFdx(vTexCoord.x);
    float _173 = dFdy(vTexCoord.y);
    vec2 _177 = fwidth(vTexCoord);
    vec4 _186 = texture(source, vTexCoord + (vec2(_170, _173) * 4.0));
    vec3 _193 = mix(_144.xyz, _186.xyz, vec3(crt.tapMix * clamp(length(_177) * 100.0, 0.0, 1.0)));
    float _239;
    float _241;
    int _237 = 0;
    float _238 = 0.0;
    for (;;)
    {
        if (_237 < crt.loopCount)
        {
            if (_237 == 1)
            {
                _241 = _238;
                int _223 = _237 + 1;
                _238 = _241;
                _237 = _223;
                continue;
            }
            float _216 = fma(_193.x * float(_237), 0.25, _238);
            if (_216 > 2.0)
            {
                _239 = _216;
                break;
            }
            _241 = _216;
            int _223 = _237 + 1;
            _238 = _241;
            _237 = _223;
            continue;
        }
        else
        {
            _239 = _238;
            break;
        }
    }
    fragColor = vec4(_193 * fma(0.100000001490116119384765625, _239, 1.0), 1.0);
}

