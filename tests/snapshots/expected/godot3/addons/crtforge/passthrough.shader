// crtforge 0.1.0: preset passthrough. No stages: every target's plain passthrough blit
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Node mode: put it on the node showing the picture (TextureRect, Sprite, a SubViewport's texture);
// set the node's texture filter to linear.
shader_type canvas_item;


void fragment()
{
    COLOR = texture(TEXTURE, UV);
}

