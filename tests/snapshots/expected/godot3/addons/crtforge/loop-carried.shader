// crtforge 0.1.0: preset loop-carried. loops (carried) after the derivative footprint tap
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Node mode: put it on the node showing the picture (TextureRect, Sprite, a SubViewport's texture);
// set the node's texture filter to linear.
shader_type canvas_item;

// taps: How much of the extra taps replaces the centre sample
uniform float tapMix : hint_range(0.0, 1.0, 0.01) = 0.3;
// loops: Number of iterations
uniform int loopCount : hint_range(0, 16, 1) = 5;

void fragment()
{
    vec4 _144 = texture(TEXTURE, UV);
    float _170 = dFdx(UV.x);
    float _173 = dFdy(UV.y);
    vec2 _177 = fwidth(UV);
    vec4 _186 = texture(TEXTURE, UV + (vec2(_170, _173) * 4.0));
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

