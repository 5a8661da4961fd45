#version 330
#ifdef GL_ARB_shading_language_420pack
#extension GL_ARB_shading_language_420pack : require
#endif

layout(binding = 0, std140) uniform CrtParams
{
    vec2 outputSize;
    int loopCount;
} crt;

layout(binding = 1) uniform sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 _105 = texture(source, vTexCoord);
    float _126 = _105.y;
    vec4 _164;
    _164 = vec4(_105.x, _126, _105.z, 1.0);
    int _141;
    vec4 _161;
    int _163 = 0;
    for (;;)
    {
        _161 = _164;
        _161.y = _126 * 0.89999997615814208984375 + (0.00999999977648258209228515625 * float(_163));
        _141 = _163 + 1;
        if (_141 >= crt.loopCount)
        {
            break;
        }
        _164 = _161;
        _163 = _141;
        continue;
    }
    fragColor = vec4(_161.xyz * _164.w, 1.0);
}

