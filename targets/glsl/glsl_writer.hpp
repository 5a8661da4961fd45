// GLSL targets (glsl450, glsl330, glsles300) through SPIRV-Cross, for OpenGL / OpenGL ES hosts.
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::glsl {

struct Options {
    int version = 450;          // #version of the output: 450, 330 or 300
    bool es = false;            // true for OpenGL ES (with version 300)
    // OpenGL clip space is y-up; flipping keeps uv (0,0) at the top of the screen, as on Vulkan.
    bool flip_vertex_y = true;
    // WebGL 2 frameworks (three.js RawShaderMaterial, PixiJS, regl) set uniforms by name: the
    // params and builtins as plain top-level uniforms (`uniform float scanlineIntensity;`) instead
    // of the std140 block.
    bool plain_uniforms = false;
};

Result<TargetOutput> generate(const TargetInput& input, const Options& options);

// The uniform block of SPIRV-Cross's plain-uniform output (`struct CrtParams {...}; uniform
// CrtParams <instance>;`) as one top-level uniform per member, each access `<instance>.x` as `x`.
// Members cannot meet a local of the same name: cross_compile renames such locals.
std::string flatten_plain_uniform_block(const std::string& text, const std::string& instance);

// The glsl450, glsl330, glsles300 and webgl2 records (crtforge/targets.hpp).
std::vector<TargetInfo> records();

}  // namespace crtforge::glsl
