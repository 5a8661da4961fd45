// GLSL targets (glsl450, glsl330, glsles300) through SPIRV-Cross, for OpenGL / OpenGL ES hosts.
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::glsl {

struct Options {
    int version = 450;          // #version of the output: 450, 330 or 300
    bool es = false;            // true for OpenGL ES (with version 300)
    // OpenGL clip space is y-up; flipping keeps uv (0,0) at the top of the screen, as on Vulkan.
    bool flip_vertex_y = true;
};

Result<TargetOutput> generate(const TargetInput& input, const Options& options);

// The glsl450, glsl330 and glsles300 records (crtforge/targets.hpp).
std::vector<TargetInfo> records();

}  // namespace crtforge::glsl
