// crtforge 0.1.0: preset bend-cross. bend (swizzle warp, edge colour) with the four-tap cross
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }

// bend: How strongly the coordinate is scaled by its squared radius
uniform float bendAmount : hint_range(0.0, 0.5, 0.01) = 0.12;
// bend: Colour shown where the warp left the screen
uniform vec4 edgeColor : hint_color = vec4(0.12549019607843137, 0.18823529411764706, 0.25098039215686274, 1.0);
// taps: How much of the extra taps replaces the centre sample
uniform float tapMix : hint_range(0.0, 1.0, 0.01) = 0.4;

void fragment()
{
    vec4 q_1 = (vec4(crt_flip_y(SCREEN_UV).xyyx) * 2.0) - vec4(1.0);
    vec2 _604 = q_1.xy;
    vec2 _612 = q_1.zw * (bendAmount * dot(_604, _604) + 1.0);
    vec4 q_2 = vec4(0.0);
    q_2.z = _612.x;
    q_2.w = _612.y;
    vec2 _619 = q_2.wz * 0.5;
    vec2 sampleUv = _619 + vec2(0.5);
    vec4 texel = textureLod(SCREEN_TEXTURE, crt_flip_y(sampleUv), 0.0);
    vec4 texel_1 = textureLod(SCREEN_TEXTURE, crt_flip_y(_619 + vec2(0.5025, 0.5)), 0.0);
    vec4 texel_2 = textureLod(SCREEN_TEXTURE, crt_flip_y(_619 + vec2(0.4975, 0.5)), 0.0);
    vec4 texel_3 = textureLod(SCREEN_TEXTURE, crt_flip_y(_619 + vec2(0.5, 0.5025)), 0.0);
    vec4 texel_4 = textureLod(SCREEN_TEXTURE, crt_flip_y(_619 + vec2(0.5, 0.4975)), 0.0);
    vec3 color_1;
    do
    {
        float _754 = sampleUv.x;
        bool _755 = _754 < 0.0;
        bool _762;
        if (!_755)
        {
            _762 = _754 > 1.0;
        }
        else
        {
            _762 = _755;
        }
        if (_762)
        {
            color_1 = edgeColor.rgb;
            break;
        }
        float _768 = sampleUv.y;
        bool _769 = _768 < 0.0;
        bool _776;
        if (!_769)
        {
            _776 = _768 > 1.0;
        }
        else
        {
            _776 = _769;
        }
        if (_776)
        {
            color_1 = edgeColor.rgb.zyx;
            break;
        }
        color_1 = mix(texel.xyz, (((texel_1.xyz + texel_2.xyz) + texel_3.xyz) + texel_4.xyz) * 0.25, vec3(tapMix));
        break;
    } while(false);
    vec4 c = vec4(color_1, 1.0);
    vec4 _824 = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 _826 = isnan(c);
    COLOR = vec4(_826.x ? vec4(0.0).x : _824.x, _826.y ? vec4(0.0).y : _824.y, _826.z ? vec4(0.0).z : _824.z, _826.w ? vec4(0.0).w : _824.w);
}

