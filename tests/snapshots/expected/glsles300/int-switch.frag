#version 300 es
precision highp float;
precision highp int;

layout(std140) uniform CrtParams
{
    vec2 outputSize;
    int bandWidth;
    float pickDim;
} crt;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 _160 = vTexCoord * crt.outputSize;
    vec4 _182 = texture(source, vTexCoord);
    int _213 = int(_160.x) - 12;
    float _225 = _160.y;
    vec3 _244 = _182.xyz * (0.02999999932944774627685546875 * mod(_225 - 4.0, -6.0) + ((-0.001000000047497451305389404296875) * float(_213 / (-3)) + (0.00999999977648258209228515625 * float(_213 % crt.bandWidth) + (0.0199999995529651641845703125 * float(_213 / crt.bandWidth) + 1.0))));
    vec3 _333;
    switch (int(_225) & 3)
    {
        case 0:
        {
            _333 = vec3(1.0, crt.pickDim, crt.pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _333 = vec3(crt.pickDim, 1.0, crt.pickDim);
            break;
        }
        default:
        {
            _333 = vec3(crt.pickDim, crt.pickDim, 1.0);
            break;
        }
    }
    float _331;
    if (vTexCoord.x > 0.5)
    {
        _331 = sqrt(max(_244.y, 0.0));
    }
    else
    {
        float _283 = _244.y;
        _331 = _283 * _283;
    }
    fragColor = vec4(_244 * _333 + vec3(((vTexCoord.y < 0.5) ? 0.00999999977648258209228515625 : (-0.00999999977648258209228515625)) * _331), 1.0);
}

