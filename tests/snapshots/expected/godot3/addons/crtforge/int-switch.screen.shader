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
    vec2 _179 = crt_flip_y(SCREEN_UV) * (1.0 / SCREEN_PIXEL_SIZE);
    vec4 _200 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
    int _233 = int(_179.x) - 12;
    float _245 = _179.y;
    vec3 _264 = _200.xyz * (0.03 * mod(_245 - 4.0, -6.0) + ((-0.001) * float(_233 / (-3)) + (0.01 * float(_233 % bandWidth) + (0.02 * float(_233 / bandWidth) + 1.0))));
    vec3 _362;
    switch (int(_245) & 3)
    {
        case 0:
        {
            _362 = vec3(1.0, pickDim, pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _362 = vec3(pickDim, 1.0, pickDim);
            break;
        }
        default:
        {
            _362 = vec3(pickDim, pickDim, 1.0);
            break;
        }
    }
    float _360;
    if (crt_flip_y(SCREEN_UV).x > 0.5)
    {
        _360 = sqrt(max(_264.y, 0.0));
    }
    else
    {
        float _303 = _264.y;
        _360 = _303 * _303;
    }
    vec4 _218 = vec4(_264 * _362 + vec3(((crt_flip_y(SCREEN_UV).y < 0.5) ? 0.01 : (-0.01)) * _360), 1.0);
    vec4 _325 = clamp(_218, vec4(-65504.0), vec4(65504.0));
    bvec4 _327 = isnan(_218);
    COLOR = vec4(_327.x ? vec4(0.0).x : _325.x, _327.y ? vec4(0.0).y : _325.y, _327.z ? vec4(0.0).z : _325.z, _327.w ? vec4(0.0).w : _325.w);
}

