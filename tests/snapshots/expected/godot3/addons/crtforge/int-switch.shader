// crtforge 0.1.0: preset int-switch. intmath bands and pick rows
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Node mode: put it on the node showing the picture (TextureRect, Sprite, a Viewport's texture);
// turn the texture's Filter flag on (Import dock, or Texture.flags).
// Needs the GLES3 renderer: it reads dFdx, which GLES2 lacks (Godot then shows the raw picture).
shader_type canvas_item;

// intmath: Width of one band (px)
uniform int bandWidth : hint_range(1, 16, 1) = 4;
// pick: Brightness of the channels a row does not favour
uniform float pickDim : hint_range(0.0, 1.0, 0.01) = 0.6;

void fragment()
{
    vec2 product = UV * round(1.0 / abs(vec2(dFdx(UV.x), dFdy(UV.y))));
    vec4 texel = texture(TEXTURE, UV);
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
    if (UV.x > 0.5)
    {
        lift_1 = sqrt(max(color.y, 0.0));
    }
    else
    {
        float color_y = color.y;
        lift_1 = color_y * color_y;
    }
    vec4 c = vec4(color * tint_1 + vec3(((UV.y < 0.5) ? 0.01 : (-0.01)) * lift_1), 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    COLOR = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

