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

vec4 _842;

void fragment()
{
    vec2 _402 = crt_flip_y(SCREEN_UV) * (1.0 / SCREEN_PIXEL_SIZE);
    vec4 _490 = (vec4(crt_flip_y(SCREEN_UV).xyyx) * 2.0) - vec4(1.0);
    vec2 _494 = _490.xy;
    vec2 _502 = _490.zw * (bendAmount * dot(_494, _494) + 1.0);
    vec4 _804;
    _804.z = _502.x;
    _804.w = _502.y;
    vec2 _511 = (_804.wz * 0.5) + vec2(0.5);
    float _517 = _511.x;
    float _520 = _511.y;
    vec3 _541 = mix(textureLod(SCREEN_TEXTURE, crt_flip_y(_511), 0.0).xyz, textureLod(SCREEN_TEXTURE, crt_flip_y(_511 + (vec2(dFdx(_517), dFdy(_520)) * 4.0)), 0.0).xyz, vec3(tapMix * clamp(length(fwidth(_511)) * 100.0, 0.0, 1.0)));
    float _548 = _541.y;
    vec4 _829;
    _829 = vec4(_541.x, _548, _541.z, 1.0);
    int _563;
    vec4 _811;
    int _828 = 0;
    for (;;)
    {
        _811 = _829;
        _811.y = _548 * 0.5 + (0.01 * float(_828));
        _563 = _828 + 1;
        if (_563 >= loopCount)
        {
            break;
        }
        _829 = _811;
        _828 = _563;
        continue;
    }
    int _587 = int(_402.x) - 10;
    float _599 = _402.y;
    vec3 _618 = (_811.xyz * _829.w) * (0.03 * mod(_599 - 4.0, -5.0) + ((-0.001) * float(_587 / (-3)) + (0.01 * float(_587 % bandWidth) + (0.02 * float(_587 / bandWidth) + 1.0))));
    vec3 _832;
    switch (int(_599) & 3)
    {
        case 0:
        {
            _832 = vec3(1.0, pickDim, pickDim);
            break;
        }
        case 1:
        case 2:
        {
            _832 = vec3(pickDim, 1.0, pickDim);
            break;
        }
        default:
        {
            _832 = vec3(pickDim, pickDim, 1.0);
            break;
        }
    }
    float _830;
    if (_517 > 0.5)
    {
        _830 = sqrt(max(_618.y, 0.0));
    }
    else
    {
        float _652 = _618.y;
        _830 = _652 * _652;
    }
    vec2 _683 = abs((_511 * 2.0) - vec2(1.0)) * shapeScale;
    vec3 _833;
    do
    {
        bool _720 = _517 < 0.0;
        bool _727;
        if (!_720)
        {
            _727 = _517 > 1.0;
        }
        else
        {
            _727 = _720;
        }
        if (_727)
        {
            _833 = edgeColor.rgb;
            break;
        }
        bool _734 = _520 < 0.0;
        bool _741;
        if (!_734)
        {
            _741 = _520 > 1.0;
        }
        else
        {
            _741 = _734;
        }
        if (_741)
        {
            _833 = edgeColor.rgb.zyx;
            break;
        }
        _833 = ((_618 * _832 + vec3(((crt_flip_y(SCREEN_UV).y < 0.5) ? 0.01 : (-0.01)) * _830)) * clamp(1.5 - max(_683.x, _683.y), 0.8, 0.2)) * (pulseDepth * sin(_599 * 0.025 + ((max(hostTime, 0.0) + (1.0 - step(0.0, hostTime)) * (TIME * (round(pulseRate * 3600.0 / 6.28318530717959) * 6.28318530717959 / 3600.0) / pulseRate)) * pulseRate)) + 1.0);
        break;
    } while(false);
    vec4 _466 = vec4(_833, 1.0);
    vec4 _755 = clamp(_466, vec4(-65504.0), vec4(65504.0));
    bvec4 _757 = isnan(_466);
    COLOR = vec4(_757.x ? vec4(0.0).x : _755.x, _757.y ? vec4(0.0).y : _755.y, _757.z ? vec4(0.0).z : _755.z, _757.w ? vec4(0.0).w : _755.w);
}

