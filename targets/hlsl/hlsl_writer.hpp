// HLSL targets (hlsl50 = Shader Model 5.0, hlsl60 = 6.0) through SPIRV-Cross, for D3D11/D3D12 hosts.
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::hlsl {

struct Options {
    int shader_model = 50;      // 50 or 60
    // D3D clip space is y-up; flipping keeps uv (0,0) at the top of the screen, as on Vulkan.
    bool flip_vertex_y = true;
};

Result<TargetOutput> generate(const TargetInput& input, const Options& options);

// The hlsl50 and hlsl60 records (crtforge/targets.hpp).
std::vector<TargetInfo> records();

}  // namespace crtforge::hlsl
