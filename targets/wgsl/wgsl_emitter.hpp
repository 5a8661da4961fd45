// crtforge's own SPIR-V -> WGSL emitter (SPIRV-Cross has no WGSL backend).
//
// Input: one or more SPIR-V shader modules (a vertex and a fragment stage from glslang, optimised or
// not). Output: ONE WGSL module holding an entry point per stage, plus the resource bindings a host
// needs to write its bind group. What it covers and how each SPIR-V construct maps is documented in
// targets/wgsl/README.md; anything outside that subset is an error naming the opcode (and the
// source line when the module carries OpLine debug info), never approximate output.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spirv_compiler.hpp"

namespace crtforge::wgsl {

struct StageInput {
    const SpirvBinary* spirv = nullptr;
    std::string entry_name;  // WGSL entry point name, e.g. "vs_main" / "fs_main"
};

struct EmitOptions {
    // Uniform-block struct name -> the name of its `var<uniform>` (e.g. CrtParams -> crt), used
    // when the SPIR-V variable itself is unnamed, as glslang's block instances usually are.
    std::map<std::string, std::string> block_instance_names;
    // The vertex stage writes clip-space y negated (SPIR-V from Vulkan GLSL has y pointing down in
    // clip space, WebGPU has it up), so the same texture coordinate lands on the same pixel row.
    bool flip_vertex_y = true;
    std::string header_comment;  // lines printed first, each prefixed with "// "
    // Textures (by their SPIR-V name) the host samples clamp-to-edge where the shader wants
    // clamp-to-border with a transparent black border, which WebGPU lacks: every sample of them is
    // multiplied by the share of its footprint inside the texture. true: sampled linearly.
    std::map<std::string, bool> emulate_border;
};

struct WgslMember {
    std::string name, wgsl_type;
    uint32_t offset = 0, size = 0;
};

// One entry of the bind group the module declares (all in @group(0) for crtforge's shaders).
struct WgslBinding {
    uint32_t group = 0, binding = 0;
    std::string name;          // the WGSL variable name
    std::string kind;          // "uniform-buffer", "texture", "sampler"
    std::string wgsl_type;     // "CrtParams", "texture_2d<f32>", "sampler"
    uint32_t size = 0;         // uniform buffers: byte size of the struct
    std::vector<WgslMember> members;  // uniform buffers: the struct's members
    std::string sample_type;   // textures: "float"
    std::string paired_with;   // texture <-> sampler split from one combined image sampler
    std::vector<std::string> stages;  // "vertex", "fragment"
    bool border_in_shader = false;    // samplers: the shader emulates clamp_to_border (EmitOptions::emulate_border)
};

struct WgslModule {
    std::string text;
    std::vector<WgslBinding> bindings;  // sorted by (group, binding)
};

// ErrorKind::Validation on failure: the SPIR-V came from crtforge's own generator.
Result<WgslModule> emit_wgsl(const std::vector<StageInput>& stages, const EmitOptions& options);

}  // namespace crtforge::wgsl
