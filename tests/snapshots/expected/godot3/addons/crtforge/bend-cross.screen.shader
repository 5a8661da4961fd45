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

vec4 _363;

void fragment()
{
    vec4 _234 = (vec4(crt_flip_y(SCREEN_UV).xyyx) * 2.0) - vec4(1.0);
    vec2 _238 = _234.xy;
    vec2 _246 = _234.zw * (bendAmount * dot(_238, _238) + 1.0);
    vec4 _346;
    _346.z = _246.x;
    _346.w = _246.y;
    vec2 _253 = _346.wz * 0.5;
    vec2 _255 = _253 + vec2(0.5);
    vec4 _193 = textureLod(SCREEN_TEXTURE, crt_flip_y(_255), 0.0);
    vec4 _262 = textureLod(SCREEN_TEXTURE, crt_flip_y(_253 + vec2(0.502499997615814208984375, 0.5)), 0.0);
    vec4 _267 = textureLod(SCREEN_TEXTURE, crt_flip_y(_253 + vec2(0.497500002384185791015625, 0.5)), 0.0);
    vec4 _274 = textureLod(SCREEN_TEXTURE, crt_flip_y(_253 + vec2(0.5, 0.502499997615814208984375)), 0.0);
    vec4 _281 = textureLod(SCREEN_TEXTURE, crt_flip_y(_253 + vec2(0.5, 0.497500002384185791015625)), 0.0);
    vec3 _353;
    do
    {
        float _298 = _255.x;
        bool _299 = _298 < 0.0;
        bool _306;
        if (!_299)
        {
            _306 = _298 > 1.0;
        }
        else
        {
            _306 = _299;
        }
        if (_306)
        {
            _353 = edgeColor.rgb;
            break;
        }
        float _312 = _255.y;
        bool _313 = _312 < 0.0;
        bool _320;
        if (!_313)
        {
            _320 = _312 > 1.0;
        }
        else
        {
            _320 = _313;
        }
        if (_320)
        {
            _353 = edgeColor.rgb.zyx;
            break;
        }
        _353 = mix(_193.xyz, (((_262.xyz + _267.xyz) + _274.xyz) + _281.xyz) * 0.25, vec3(tapMix));
        break;
    } while(false);
    COLOR = vec4(_353, 1.0);
}

