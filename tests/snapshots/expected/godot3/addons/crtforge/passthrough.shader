// crtforge 0.1.0: preset passthrough. No stages: every target's plain passthrough blit
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Node mode: put it on the node showing the picture (TextureRect, Sprite, a Viewport's texture);
// turn the texture's Filter flag on (Import dock, or Texture.flags).
// Needs the GLES3 renderer: it reads dFdx, which GLES2 lacks (Godot then shows the raw picture).
shader_type canvas_item;


void fragment()
{
    vec4 c = texture(TEXTURE, UV);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    COLOR = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

