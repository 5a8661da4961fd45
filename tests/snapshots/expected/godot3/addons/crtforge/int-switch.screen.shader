// crtforge 0.1.0: preset int-switch. intmath bands and pick rows
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }

// intmath: Width of one band (px)
uniform int bandWidth : hint_range(1, 16, 1) = 4;
// pick: Brightness of the channels a row does not favour
uniform float pickDim : hint_range(0.0, 1.0, 0.01) = 0.6;

void fragment()
{
    vec2 _160 = crt_flip_y(SCREEN_UV) * (1.0 / SCREEN_PIXEL_SIZE);
    vec4 _182 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
    int _213 = int(_160.x) - 12;
    float _225 = _160.y;
    vec3 _244 = _182.xyz * (0.02999999932944774627685546875 * mod(_225 - 4.0, -6.0) + ((-0.001000000047497451305389404296875) * float(_213 / (-3)) + (0.00999999977648258209228515625 * float(_213 % bandWidth) + (0.0199999995529651641845703125 * float(_213 / bandWidth) + 1.0))));
    vec3 _333;
    switch (int(_225) & 3)
    {
        case 0:
        {
            _333 = vec3(1.0, pickDim, pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _333 = vec3(pickDim, 1.0, pickDim);
            break;
        }
        default:
        {
            _333 = vec3(pickDim, pickDim, 1.0);
            break;
        }
    }
    float _331;
    if (crt_flip_y(SCREEN_UV).x > 0.5)
    {
        _331 = sqrt(max(_244.y, 0.0));
    }
    else
    {
        float _283 = _244.y;
        _331 = _283 * _283;
    }
    COLOR = vec4(_244 * _333 + vec3(((crt_flip_y(SCREEN_UV).y < 0.5) ? 0.00999999977648258209228515625 : (-0.00999999977648258209228515625)) * _331), 1.0);
}

