// crtforge 0.1.0: preset loop-component. loops (component) alone
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }

// loops: Number of iterations
uniform int loopCount : hint_range(0, 16, 1) = 3;

void fragment()
{
    vec4 _105 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
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
        if (_141 >= loopCount)
        {
            break;
        }
        _164 = _161;
        _163 = _141;
        continue;
    }
    COLOR = vec4(_161.xyz * _164.w, 1.0);
}

