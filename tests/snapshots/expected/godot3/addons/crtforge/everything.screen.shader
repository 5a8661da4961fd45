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

void fragment()
{
    vec2 product = crt_flip_y(SCREEN_UV) * round(1.0 / SCREEN_PIXEL_SIZE);
    vec4 q_1 = (vec4(crt_flip_y(SCREEN_UV).xyyx) * 2.0) - vec4(1.0);
    vec2 q_xy = q_1.xy;
    vec2 product_1 = q_1.zw * (bendAmount * dot(q_xy, q_xy) + 1.0);
    vec4 q_2 = vec4(0.0);
    q_2.z = product_1.x;
    q_2.w = product_1.y;
    vec2 sampleUv = (q_2.wz * 0.5) + vec2(0.5);
    float sampleUv_x = sampleUv.x;
    float sampleUv_y = sampleUv.y;
    vec3 color_2 = mix(textureLod(SCREEN_TEXTURE, crt_flip_y(sampleUv), 0.0).xyz, textureLod(SCREEN_TEXTURE, crt_flip_y(sampleUv + (vec2(dFdx(sampleUv_x), dFdy(sampleUv_y)) * 4.0)), 0.0).xyz, vec3(tapMix * clamp(length(fwidth(sampleUv)) * 100.0, 0.0, 1.0)));
    float color_y = color_2.y;
    vec4 s_2;
    s_2 = vec4(color_2.x, color_y, color_2.z, 1.0);
    int k_1_1;
    vec4 s_1_1;
    int k_2 = 0;
    for (int crtforge_loop0 = 0; true; crtforge_loop0 += 0)
    {
        s_1_1 = s_2;
        s_1_1.y = color_y * 0.5 + (0.01 * float(k_2));
        k_1_1 = k_2 + 1;
        if (k_1_1 >= loopCount)
        {
            break;
        }
        s_2 = s_1_1;
        k_2 = k_1_1;
        continue;
    }
    int x = int(product.x) - 10;
    float part = product.y;
    vec3 color_3 = (s_1_1.xyz * s_2.w) * (0.03 * mod(part - 4.0, -5.0) + ((-0.001) * float(x / (-3)) + (0.01 * float(x % bandWidth) + (0.02 * float(x / bandWidth) + 1.0))));
    vec3 tint_1;
    switch (int(part) & 3)
    {
        case 0:
        {
            tint_1 = vec3(1.0, pickDim, pickDim);
            break;
        }
        case 1:
        case 2:
        {
            tint_1 = vec3(pickDim, 1.0, pickDim);
            break;
        }
        default:
        {
            tint_1 = vec3(pickDim, pickDim, 1.0);
            break;
        }
    }
    float lift_1;
    if (sampleUv_x > 0.5)
    {
        lift_1 = sqrt(max(color_3.y, 0.0));
    }
    else
    {
        float color_y_1 = color_3.y;
        lift_1 = color_y_1 * color_y_1;
    }
    vec2 d = abs((sampleUv * 2.0) - vec2(1.0)) * shapeScale;
    vec3 color_1;
    do
    {
        bool cond_3 = sampleUv_x < 0.0;
        bool cond_2;
        if (!cond_3)
        {
            cond_2 = sampleUv_x > 1.0;
        }
        else
        {
            cond_2 = cond_3;
        }
        if (cond_2)
        {
            color_1 = edgeColor.rgb;
            break;
        }
        bool cond_4 = sampleUv_y < 0.0;
        bool cond_1_1;
        if (!cond_4)
        {
            cond_1_1 = sampleUv_y > 1.0;
        }
        else
        {
            cond_1_1 = cond_4;
        }
        if (cond_1_1)
        {
            color_1 = edgeColor.rgb.zyx;
            break;
        }
        color_1 = ((color_3 * tint_1 + vec3(((crt_flip_y(SCREEN_UV).y < 0.5) ? 0.01 : (-0.01)) * lift_1)) * min(max(1.5 - max(d.x, d.y), 0.8), 0.2)) * (pulseDepth * sin(part * 0.025 + ((max(hostTime, 0.0) + (1.0 - step(0.0, hostTime)) * (TIME * (round(pulseRate * 3600.0 / uintBitsToFloat(uint(1086918619))) * uintBitsToFloat(uint(1086918619)) / 3600.0) / pulseRate)) * pulseRate)) + 1.0);
        break;
    } while(false);
    vec4 c = vec4(color_1, 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond_5 = isnan(c);
    COLOR = vec4(cond_5.x ? 0.0 : clamped.x, cond_5.y ? 0.0 : clamped.y, cond_5.z ? 0.0 : clamped.z, cond_5.w ? 0.0 : clamped.w);
}

