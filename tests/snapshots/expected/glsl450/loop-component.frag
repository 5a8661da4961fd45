#version 450

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    int loopCount;
} crt;

layout(binding = 1) uniform sampler2D source;

layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 _123 = texture(source, vTexCoord);
    float _146 = _123.y;
    vec4 _193;
    _193 = vec4(_123.x, _146, _123.z, 1.0);
    int _161;
    vec4 _190;
    int _192 = 0;
    for (;;)
    {
        _190 = _193;
        _190.y = fma(_146, 0.9, 0.01 * float(_192));
        _161 = _192 + 1;
        if (_161 >= crt.loopCount)
        {
            break;
        }
        _193 = _190;
        _192 = _161;
        continue;
    }
    vec4 _136 = vec4(_190.xyz * _193.w, 1.0);
    fragColor = mix(clamp(_136, vec4(-65504.0), vec4(65504.0)), vec4(0.0), isnan(_136));
}

