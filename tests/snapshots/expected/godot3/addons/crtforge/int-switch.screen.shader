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
    vec2 product = crt_flip_y(SCREEN_UV) * round(1.0 / SCREEN_PIXEL_SIZE);
    vec4 texel = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
    int x = int(product.x) - 12;
    float part = product.y;
    vec3 color = texel.xyz * (0.03 * mod(part - 4.0, -6.0) + ((-0.001) * float(x / (-3)) + (0.01 * float(x % bandWidth) + (0.02 * float(x / bandWidth) + 1.0))));
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
    if (crt_flip_y(SCREEN_UV).x > 0.5)
    {
        lift_1 = sqrt(max(color.y, 0.0));
    }
    else
    {
        float color_y = color.y;
        lift_1 = color_y * color_y;
    }
    vec4 c = vec4(color * tint_1 + vec3(((crt_flip_y(SCREEN_UV).y < 0.5) ? 0.01 : (-0.01)) * lift_1), 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    COLOR = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

