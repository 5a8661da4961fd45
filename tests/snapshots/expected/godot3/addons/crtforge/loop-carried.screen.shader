// crtforge 0.1.0: preset loop-carried. loops (carried) after the derivative footprint tap
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }

// taps: How much of the extra taps replaces the centre sample
uniform float tapMix : hint_range(0.0, 1.0, 0.01) = 0.3;
// loops: Number of iterations
uniform int loopCount : hint_range(0, 16, 1) = 5;

void fragment()
{
    vec4 texel = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
    float value = dFdx(crt_flip_y(SCREEN_UV).x);
    float value_1 = dFdy(crt_flip_y(SCREEN_UV).y);
    vec2 value_2 = fwidth(crt_flip_y(SCREEN_UV));
    vec4 texel_1 = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV) + (vec2(value, value_1) * 4.0)), 0.0);
    vec3 color = mix(texel.xyz, texel_1.xyz, vec3(tapMix * clamp(length(value_2) * 100.0, 0.0, 1.0)));
    float sum_2_1;
    float sum_1_1;
    int k_1 = 0;
    float sum_3 = 0.0;
    for (int crtforge_loop0 = 0; true; crtforge_loop0 += 0)
    {
        if (k_1 < loopCount)
        {
            if (k_1 == 1)
            {
                sum_1_1 = sum_3;
                int k_2 = k_1 + 1;
                sum_3 = sum_1_1;
                k_1 = k_2;
                continue;
            }
            float sum_4 = (color.x * float(k_1)) * 0.25 + sum_3;
            if (sum_4 > 2.0)
            {
                sum_2_1 = sum_4;
                break;
            }
            sum_1_1 = sum_4;
            int k_2_1 = k_1 + 1;
            sum_3 = sum_1_1;
            k_1 = k_2_1;
            continue;
        }
        else
        {
            sum_2_1 = sum_3;
            break;
        }
    }
    vec4 c = vec4(color * (0.1 * sum_2_1 + 1.0), 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    COLOR = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

