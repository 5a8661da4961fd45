// crtforge 0.1.0: preset passthrough. No stages: every target's plain passthrough blit
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
shader_type canvas_item;


void fragment()
{
    COLOR = texture(SCREEN_TEXTURE, SCREEN_UV);
}

