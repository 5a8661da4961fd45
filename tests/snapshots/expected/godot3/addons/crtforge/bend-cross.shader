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

void fragment()
{
    vec4 q_1 = (vec4(UV.xyyx) * 2.0) - vec4(1.0);
    vec2 q_xy = q_1.xy;
    vec2 product = q_1.zw * (bendAmount * dot(q_xy, q_xy) + 1.0);
    vec4 q_2 = vec4(0.0);
    q_2.z = product.x;
    q_2.w = product.y;
    vec2 product_1 = q_2.wz * 0.5;
    vec2 sampleUv = product_1 + vec2(0.5);
    vec4 texel = texture(TEXTURE, sampleUv);
    vec4 texel_1 = texture(TEXTURE, product_1 + vec2(0.5025, 0.5));
    vec4 texel_2 = texture(TEXTURE, product_1 + vec2(0.4975, 0.5));
    vec4 texel_3 = texture(TEXTURE, product_1 + vec2(0.5, 0.5025));
    vec4 texel_4 = texture(TEXTURE, product_1 + vec2(0.5, 0.4975));
    vec3 color_1;
    do
    {
        float sampleUv_x = sampleUv.x;
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
        float sampleUv_y = sampleUv.y;
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
        color_1 = mix(texel.xyz, (((texel_1.xyz + texel_2.xyz) + texel_3.xyz) + texel_4.xyz) * 0.25, vec3(tapMix));
        break;
    } while(false);
    vec4 c = vec4(color_1, 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond_5 = isnan(c);
    COLOR = vec4(cond_5.x ? 0.0 : clamped.x, cond_5.y ? 0.0 : clamped.y, cond_5.z ? 0.0 : clamped.z, cond_5.w ? 0.0 : clamped.w);
}

