#version 300 es
precision highp float;
precision highp int;

uniform vec2 outputSize;
uniform int bandWidth;
uniform float pickDim;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec2 product = vTexCoord * outputSize;
    vec4 texel = texture(source, vTexCoord);
    int x = int(product.x) - 12;
    float part = product.y;
    vec3 color = texel.xyz * (0.03 * mod(part - 4.0, -6.0) + ((-0.001) * float(x / (-3)) + (0.01 * float(x % bandWidth) + (0.02 * float(x / bandWidth) + 1.0))));
    vec3 tint;
    switch (int(part) & 3)
    {
        case 0:
        {
            tint = vec3(1.0, pickDim, pickDim);
            break;
        }
        case 1:
        case 2:
        {
            tint = vec3(pickDim, 1.0, pickDim);
            break;
        }
        default:
        {
            tint = vec3(pickDim, pickDim, 1.0);
            break;
        }
    }
    float lift;
    if (vTexCoord.x > 0.5)
    {
        lift = sqrt(max(color.y, 0.0));
    }
    else
    {
        float color_y = color.y;
        lift = color_y * color_y;
    }
    vec4 c = vec4(color * tint + vec3(((vTexCoord.y < 0.5) ? 0.01 : (-0.01)) * lift), 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    fragColor = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

