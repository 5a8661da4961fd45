// Godot targets (godot4: .gdshader, godot3: .shader): canvas_item shaders written from the same
// SPIR-V as every other target, by a SPIRV-Cross GLSL compiler whose header, entry point and
// resources are remapped onto Godot's dialect and builtins. Uniforms carry the spec: hint_range
// with step and default, source_color / hint_color for colours.
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::godot {

enum class Mode {
    NodeTexture,  // reads the node's own TEXTURE at UV (TextureRect, Sprite, SubViewport texture)
    Screen,       // post-processes the screen on a full-screen ColorRect
};

struct Options {
    int godot_version = 4;         // 4 (shader_type canvas_item; .gdshader) or 3 (.shader)
    Mode mode = Mode::NodeTexture;
};

// The shader text for one mode, from modules already in Godot's types (in_godot_types).
Result<std::string> generate_shader(const TargetInput& input, const Options& options);

// Both modes, the ShaderMaterial resource (.tres) of the node-texture shader, and a README: the
// files of addons/crtforge/ for one preset.
Result<TargetOutput> generate(const TargetInput& input, int godot_version);

// The `shader_param/<name> = <value>` lines (shader_parameter/ in Godot 4) that set every
// runtime param of a ShaderMaterial to the preset's value.
std::vector<std::string> material_param_lines(const Variant& variant, int godot_version);

// Godot's pass viewports are 8-bit or half-float RGBA: the statement that ends the fragment() of a
// pass stored in `format` where that stores less (r16f, rg16f, rgb10a2; rgba8_srgb, held as half
// floats, rounded to the linear value of its nearest sRGB 8-bit code), reducing COLOR to what the
// format holds, so readers see what RetroArch's see; "" where Godot stores the format as it is
// (rgba32f as half floats).
std::string format_reduction(PixelFormat format);

// ".gdshader" (Godot 4) or ".shader" (Godot 3).
const char* shader_extension(int godot_version);

// The godot4 and godot3 records (crtforge/targets.hpp).
std::vector<TargetInfo> records();

}  // namespace crtforge::godot
