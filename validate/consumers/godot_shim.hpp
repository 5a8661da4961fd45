// The Godot shim: turns a crtforge canvas_item shader back into Vulkan GLSL by wrapping it in a
// prelude that declares what Godot itself would provide — TEXTURE / screen texture, UV / SCREEN_UV,
// COLOR, TEXTURE_PIXEL_SIZE, SCREEN_PIXEL_SIZE, TIME — and turning each `uniform T name : hint =
// value;` into a member of one std140 block. Used to compile-check both dialects and to render
// godot4 (no Godot 4 is installable here).
//
// A program pass's shader (an imported RetroArch pass) also has `varying` lines and a vertex():
// those become a second Vulkan GLSL module, the vertex stage, whose outputs the fragment stage reads
// at the same locations (UV is its input at location 0).
//
// Limits: it understands the dialect crtforge emits (one uniform and one varying declaration per
// line, no light() function); it does not implement Godot's own
// compiler checks, so it proves the shader is valid GLSL with Godot's builtins and renders the same
// math, not that every Godot version accepts every construct.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/value.hpp"

namespace crtforge {
class ConsumerEngines;
}

namespace crtforge::consumers {

// Godot's TIME wraps at rendering/limits/time/time_rollover_secs (3600 s by default): both Godot
// consumers pin TIME to the frame's time modulo this, as the engine would show it.
constexpr double kGodotTimeRollover = 3600.0;

struct ShimUniform {
    std::string type;     // float, int, vec3, vec4, sampler2D
    std::string name;
    std::string value;    // the declaration's default, as written (may be empty)
};

struct ShimTexture {
    std::string name;      // a `uniform sampler2D` of the shader (other than a screen texture)
    uint32_t binding = 0;  // its Vulkan binding in the shim: 2, 3, ... in declaration order
};

struct ShimShader {
    std::string glsl;                    // Vulkan GLSL 450 for glslang
    std::string vertex_glsl;             // the vertex stage's, where the shader has a vertex() ("" if not)
    std::vector<ShimUniform> uniforms;   // non-sampler uniforms, in declaration order
    std::vector<ShimTexture> textures;   // sampler uniforms other than the screen texture
    bool screen_mode = false;            // reads SCREEN_UV and the screen texture
};

Result<ShimShader> wrap_in_shim(const std::string& godot_shader, int godot_version);

// The compile check both Godot consumers run on each shader: wrapped in the shim, glslang must
// accept it. A rejection is ErrorKind::Validation.
Status compile_through_shim(const std::string& godot_shader, int godot_version, ConsumerEngines& engines);

}  // namespace crtforge::consumers
