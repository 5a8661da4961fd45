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
    vec2 _179 = vTexCoord * crt.outputSize;
    vec4 _200 = texture(source, vTexCoord);
    int _233 = int(_179.x) - 12;
    float _245 = _179.y;
    vec3 _264 = _200.xyz * (0.03 * mod(_245 - 4.0, -6.0) + ((-0.001) * float(_233 / (-3)) + (0.01 * float(_233 % crt.bandWidth) + (0.02 * float(_233 / crt.bandWidth) + 1.0))));
    vec3 _362;
    switch (int(_245) & 3)
    {
        case 0:
        {
            _362 = vec3(1.0, crt.pickDim, crt.pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _362 = vec3(crt.pickDim, 1.0, crt.pickDim);
            break;
        }
        default:
        {
            _362 = vec3(crt.pickDim, crt.pickDim, 1.0);
            break;
        }
    }
    float _360;
    if (vTexCoord.x > 0.5)
    {
        _360 = sqrt(max(_264.y, 0.0));
    }
    else
    {
        float _303 = _264.y;
        _360 = _303 * _303;
    }
    vec4 _218 = vec4(_264 * _362 + vec3(((vTexCoord.y < 0.5) ? 0.01 : (-0.01)) * _360), 1.0);
    vec4 _325 = clamp(_218, vec4(-65504.0), vec4(65504.0));
    bvec4 _327 = isnan(_218);
    fragColor = vec4(_327.x ? vec4(0.0).x : _325.x, _327.y ? vec4(0.0).y : _325.y, _327.z ? vec4(0.0).z : _325.z, _327.w ? vec4(0.0).w : _325.w);
}

