// crtforge 0.1.0: preset loop-carried. loops (carried) after the derivative footprint tap
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }

// taps: How much of the extra taps replaces the centre sample
uniform float tapMix : hint_range(0.0, 1.0, 0.01) = 0.3;
// loops: Number of iterations
uniform int loopCount : hint_range(0, 16, 1) = 5;

void fragment()
{
    vec4 _162 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
    float _190 = dFdx(crt_flip_y(SCREEN_UV).x);
    float _193 = dFdy(crt_flip_y(SCREEN_UV).y);
    vec2 _197 = fwidth(crt_flip_y(SCREEN_UV));
    vec4 _206 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV) + (vec2(_190, _193) * 4.0)), 0.0);
    vec3 _213 = mix(_162.xyz, _206.xyz, vec3(tapMix * clamp(length(_197) * 100.0, 0.0, 1.0)));
    float _268;
    float _270;
    int _266 = 0;
    float _267 = 0.0;
    for (;;)
    {
        if (_266 < loopCount)
        {
            if (_266 == 1)
            {
                _270 = _267;
                int _243 = _266 + 1;
                _267 = _270;
                _266 = _243;
                continue;
            }
            float _236 = (_213.x * float(_266)) * 0.25 + _267;
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
    vec4 _180 = vec4(_213 * (0.1 * _268 + 1.0), 1.0);
    vec4 _255 = clamp(_180, vec4(-65504.0), vec4(65504.0));
    bvec4 _257 = isnan(_180);
    COLOR = vec4(_257.x ? vec4(0.0).x : _255.x, _257.y ? vec4(0.0).y : _255.y, _257.z ? vec4(0.0).z : _255.z, _257.w ? vec4(0.0).w : _255.w);
}

