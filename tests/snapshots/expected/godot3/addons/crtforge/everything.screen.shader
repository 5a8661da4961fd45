// crtforge 0.1.0: preset everything. Every snapshot stage enabled, with spec defaults except where noted
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
// Time: crtforge_pipeline.gd (the exported scene) sets hostTime every frame to the exact phase time,
// seconds reduced modulo 2*pi/pulseRate in double precision. Without it (hostTime < 0) the shader
// uses TIME, which wraps at rendering/limits/time/time_rollover_secs (3600 s by default): then pulseRate is
// rounded to a multiple of 2*pi/3600 rad/s so the motion stays continuous across the wrap, and the
// phase drifts from the exact one by up to t * pi/3600 rad at t seconds.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }

// bend: How strongly the coordinate is scaled by its squared radius
uniform float bendAmount : hint_range(0.0, 0.5, 0.01) = 0.1;
// bend: Colour shown where the warp left the screen
uniform vec4 edgeColor : hint_color = vec4(0.06274509803921569, 0.12549019607843137, 0.18823529411764706, 1.0);
// taps: How much of the extra taps replaces the centre sample
uniform float tapMix : hint_range(0.0, 1.0, 0.01) = 0.5;
// loops: Number of iterations
uniform int loopCount : hint_range(0, 16, 1) = 4;
// intmath: Width of one band (px)
uniform int bandWidth : hint_range(1, 16, 1) = 3;
// pick: Brightness of the channels a row does not favour
uniform float pickDim : hint_range(0.0, 1.0, 0.01) = 0.75;
// shape: Multiplier on the distance from the centre
uniform float shapeScale : hint_range(0.0, 2.0, 0.01) = 1.0;
// pulse: Amplitude of the wave
uniform float pulseDepth : hint_range(0.0, 0.2, 0.005) = 0.05;
// pulse: Phase speed of the wave (rad/s)
uniform float pulseRate : hint_range(0.5, 20.0, 0.5) = 6.0;
// Seconds reduced exactly by the host (crtforge_pipeline.gd); negative: use TIME.
uniform float hostTime = -1.0;

vec4 _812;

void fragment()
{
    vec2 _385 = crt_flip_y(SCREEN_UV) * (1.0 / SCREEN_PIXEL_SIZE);
    vec4 _471 = (vec4(crt_flip_y(SCREEN_UV).xyyx) * 2.0) - vec4(1.0);
    vec2 _475 = _471.xy;
    vec2 _483 = _471.zw * (bendAmount * dot(_475, _475) + 1.0);
    vec4 _776;
    _776.z = _483.x;
    _776.w = _483.y;
    vec2 _492 = (_776.wz * 0.5) + vec2(0.5);
    float _498 = _492.x;
    float _501 = _492.y;
    vec3 _522 = mix(textureLod(SCREEN_TEXTURE, crt_flip_y(_492), 0.0).xyz, textureLod(SCREEN_TEXTURE, crt_flip_y(_492 + (vec2(dFdx(_498), dFdy(_501)) * 4.0)), 0.0).xyz, vec3(tapMix * clamp(length(fwidth(_492)) * 100.0, 0.0, 1.0)));
    float _529 = _522.y;
    vec4 _801;
    _801 = vec4(_522.x, _529, _522.z, 1.0);
    int _544;
    vec4 _783;
    int _800 = 0;
    for (;;)
    {
        _783 = _801;
        _783.y = _529 * 0.5 + (0.00999999977648258209228515625 * float(_800));
        _544 = _800 + 1;
        if (_544 >= loopCount)
        {
            break;
        }
        _801 = _783;
        _800 = _544;
        continue;
    }
    int _568 = int(_385.x) - 10;
    float _580 = _385.y;
    vec3 _599 = (_783.xyz * _801.w) * (0.02999999932944774627685546875 * mod(_580 - 4.0, -5.0) + ((-0.001000000047497451305389404296875) * float(_568 / (-3)) + (0.00999999977648258209228515625 * float(_568 % bandWidth) + (0.0199999995529651641845703125 * float(_568 / bandWidth) + 1.0))));
    vec3 _804;
    switch (int(_580) & 3)
    {
        case 0:
        {
            _804 = vec3(1.0, pickDim, pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _804 = vec3(pickDim, 1.0, pickDim);
            break;
        }
        default:
        {
            _804 = vec3(pickDim, pickDim, 1.0);
            break;
        }
    }
    float _802;
    if (_498 > 0.5)
    {
        _802 = sqrt(max(_599.y, 0.0));
    }
    else
    {
        float _633 = _599.y;
        _802 = _633 * _633;
    }
    vec2 _664 = abs((_492 * 2.0) - vec2(1.0)) * shapeScale;
    vec3 _805;
    do
    {
        bool _701 = _498 < 0.0;
        bool _708;
        if (!_701)
        {
            _708 = _498 > 1.0;
        }
        else
        {
            _708 = _701;
        }
        if (_708)
        {
            _805 = edgeColor.rgb;
            break;
        }
        bool _715 = _501 < 0.0;
        bool _722;
        if (!_715)
        {
            _722 = _501 > 1.0;
        }
        else
        {
            _722 = _715;
        }
        if (_722)
        {
            _805 = edgeColor.rgb.zyx;
            break;
        }
        _805 = ((_599 * _804 + vec3(((crt_flip_y(SCREEN_UV).y < 0.5) ? 0.00999999977648258209228515625 : (-0.00999999977648258209228515625)) * _802)) * clamp(1.5 - max(_664.x, _664.y), 0.800000011920928955078125, 0.20000000298023223876953125)) * (pulseDepth * sin(_580 * 0.02500000037252902984619140625 + ((max(hostTime, 0.0) + (1.0 - step(0.0, hostTime)) * (TIME * (round(pulseRate * 3600.0 / 6.28318530717959) * 6.28318530717959 / 3600.0) / pulseRate)) * pulseRate)) + 1.0);
        break;
    } while(false);
    COLOR = vec4(_805, 1.0);
}

