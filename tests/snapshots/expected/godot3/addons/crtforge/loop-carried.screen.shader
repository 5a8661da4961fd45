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
    vec4 _144 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
    float _170 = dFdx(crt_flip_y(SCREEN_UV).x);
    float _173 = dFdy(crt_flip_y(SCREEN_UV).y);
    vec2 _177 = fwidth(crt_flip_y(SCREEN_UV));
    vec4 _186 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV) + (vec2(_170, _173) * 4.0)), 0.0);
    vec3 _193 = mix(_144.xyz, _186.xyz, vec3(tapMix * clamp(length(_177) * 100.0, 0.0, 1.0)));
    float _239;
    float _241;
    int _237 = 0;
    float _238 = 0.0;
    for (;;)
    {
        if (_237 < loopCount)
        {
            if (_237 == 1)
            {
                _241 = _238;
                int _223 = _237 + 1;
                _238 = _241;
                _237 = _223;
                continue;
            }
            float _216 = (_193.x * float(_237)) * 0.25 + _238;
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
    COLOR = vec4(_193 * (0.100000001490116119384765625 * _239 + 1.0), 1.0);
}

