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
    vec4 texel = texture(TEXTURE, UV);
    float texel_y = texel.y;
    vec4 s_2;
    s_2 = vec4(texel.x, texel_y, texel.z, 1.0);
    int k_1_1;
    vec4 s_1_1;
    int k_2 = 0;
    for (int crtforge_loop0 = 0; true; crtforge_loop0 += 0)
    {
        s_1_1 = s_2;
        s_1_1.y = texel_y * 0.9 + (0.01 * float(k_2));
        k_1_1 = k_2 + 1;
        if (k_1_1 >= loopCount)
        {
            break;
        }
        s_2 = s_1_1;
        k_2 = k_1_1;
        continue;
    }
    vec4 c = vec4(s_1_1.xyz * s_2.w, 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    COLOR = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

