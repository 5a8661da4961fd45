#version 300 es
precision highp float;
precision highp int;

vec4 _1032;

uniform vec2 outputSize;
uniform float bendAmount;
uniform vec3 edgeColor;
uniform float tapMix;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    vec4 q = (vec4(vTexCoord.xyyx) * 2.0) - vec4(1.0);
    vec2 _605 = q.xy;
    vec2 _613 = q.zw * (bendAmount * dot(_605, _605) + 1.0);
    vec4 q_1;
    q_1.z = _613.x;
    q_1.w = _613.y;
    vec2 _620 = q_1.wz * 0.5;
    vec2 sampleUv = _620 + vec2(0.5);
    vec4 texel = texture(source, sampleUv);
    vec4 texel_1 = texture(source, _620 + vec2(0.5025, 0.5));
    vec4 texel_2 = texture(source, _620 + vec2(0.4975, 0.5));
    vec4 texel_3 = texture(source, _620 + vec2(0.5, 0.5025));
    vec4 texel_4 = texture(source, _620 + vec2(0.5, 0.4975));
    vec3 color;
    do
    {
        float _755 = sampleUv.x;
        bool _756 = _755 < 0.0;
        bool _763;
        if (!_756)
        {
            _763 = _755 > 1.0;
        }
        else
        {
            _763 = _756;
        }
        if (_763)
        {
            color = edgeColor;
            break;
        }
        float _769 = sampleUv.y;
        bool _770 = _769 < 0.0;
        bool _777;
        if (!_770)
        {
            _777 = _769 > 1.0;
        }
        else
        {
            _777 = _770;
        }
        if (_777)
        {
            color = edgeColor.zyx;
            break;
        }
        color = mix(texel.xyz, (((texel_1.xyz + texel_2.xyz) + texel_3.xyz) + texel_4.xyz) * 0.25, vec3(tapMix));
        break;
    } while(false);
    vec4 c = vec4(color, 1.0);
    vec4 _825 = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 _827 = isnan(c);
    fragColor = vec4(_827.x ? vec4(0.0).x : _825.x, _827.y ? vec4(0.0).y : _825.y, _827.z ? vec4(0.0).z : _825.z, _827.w ? vec4(0.0).w : _825.w);
}

