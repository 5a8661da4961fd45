// crtforge 0.1.0: preset loop-component. loops (component) alone
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Node mode: put it on the node showing the picture (TextureRect, Sprite, a Viewport's texture);
// turn the texture's Filter flag on (Import dock, or Texture.flags).
// Needs the GLES3 renderer: it reads dFdx, which GLES2 lacks (Godot then shows the raw picture).
shader_type canvas_item;

// loops: Number of iterations
uniform int loopCount : hint_range(0, 16, 1) = 3;

void fragment()
{
    vec4 _123 = texture(TEXTURE, UV);
    float _146 = _123.y;
    vec4 _193;
    _193 = vec4(_123.x, _146, _123.z, 1.0);
    int _161;
    vec4 _190;
    int _192 = 0;
    for (;;)
    {
        _190 = _193;
        _190.y = _146 * 0.9 + (0.01 * float(_192));
        _161 = _192 + 1;
        if (_161 >= loopCount)
        {
            break;
        }
        _193 = _190;
        _192 = _161;
        continue;
    }
    vec4 _136 = vec4(_190.xyz * _193.w, 1.0);
    vec4 _180 = clamp(_136, vec4(-65504.0), vec4(65504.0));
    bvec4 _182 = isnan(_136);
    COLOR = vec4(_182.x ? vec4(0.0).x : _180.x, _182.y ? vec4(0.0).y : _180.y, _182.z ? vec4(0.0).z : _180.z, _182.w ? vec4(0.0).w : _180.w);
}

