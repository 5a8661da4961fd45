// crtforge 0.1.0: preset bend-cross. bend (swizzle warp, edge colour) with the four-tap cross
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Node mode: put it on the node showing the picture (TextureRect, Sprite, a Viewport's texture);
// turn the texture's Filter flag on (Import dock, or Texture.flags).
// Needs the GLES3 renderer: it reads dFdx, which GLES2 lacks (Godot then shows the raw picture).
shader_type canvas_item;

// bend: How strongly the coordinate is scaled by its squared radius
uniform float bendAmount : hint_range(0.0, 0.5, 0.01) = 0.12;
// bend: Colour shown where the warp left the screen
uniform vec4 edgeColor : hint_color = vec4(0.12549019607843137, 0.18823529411764706, 0.25098039215686274, 1.0);
// taps: How much of the extra taps replaces the centre sample
uniform float tapMix : hint_range(0.0, 1.0, 0.01) = 0.4;

vec4 _393;

void fragment()
{
    vec4 _253 = (vec4(UV.xyyx) * 2.0) - vec4(1.0);
    vec2 _257 = _253.xy;
    vec2 _265 = _253.zw * (bendAmount * dot(_257, _257) + 1.0);
    vec4 _374;
    _374.z = _265.x;
    _374.w = _265.y;
    vec2 _272 = _374.wz * 0.5;
    vec2 _274 = _272 + vec2(0.5);
    vec4 _210 = texture(TEXTURE, _274);
    vec4 _281 = texture(TEXTURE, _272 + vec2(0.5025, 0.5));
    vec4 _286 = texture(TEXTURE, _272 + vec2(0.4975, 0.5));
    vec4 _293 = texture(TEXTURE, _272 + vec2(0.5, 0.5025));
    vec4 _300 = texture(TEXTURE, _272 + vec2(0.5, 0.4975));
    vec3 _381;
    do
    {
        float _317 = _274.x;
        bool _318 = _317 < 0.0;
        bool _325;
        if (!_318)
        {
            _325 = _317 > 1.0;
        }
        else
        {
            _325 = _318;
        }
        if (_325)
        {
            _381 = edgeColor.rgb;
            break;
        }
        float _331 = _274.y;
        bool _332 = _331 < 0.0;
        bool _339;
        if (!_332)
        {
            _339 = _331 > 1.0;
        }
        else
        {
            _339 = _332;
        }
        if (_339)
        {
            _381 = edgeColor.rgb.zyx;
            break;
        }
        _381 = mix(_210.xyz, (((_281.xyz + _286.xyz) + _293.xyz) + _300.xyz) * 0.25, vec3(tapMix));
        break;
    } while(false);
    vec4 _228 = vec4(_381, 1.0);
    vec4 _353 = clamp(_228, vec4(-65504.0), vec4(65504.0));
    bvec4 _355 = isnan(_228);
    COLOR = vec4(_355.x ? vec4(0.0).x : _353.x, _355.y ? vec4(0.0).y : _353.y, _355.z ? vec4(0.0).z : _353.z, _355.w ? vec4(0.0).w : _353.w);
}

