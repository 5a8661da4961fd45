// crtforge 0.1.0: preset passthrough. No stages: every target's plain passthrough blit
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }


void fragment()
{
    vec4 c = textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    COLOR = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

