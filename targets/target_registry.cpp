// The list of targets and dispatch to each target's Generate().
#include "crtforge/targets.hpp"

#include "targets/glsl/glsl_writer.hpp"
#include "targets/godot/godot_writer.hpp"
#include "targets/hlsl/hlsl_writer.hpp"
#include "targets/spirv/spirv_writer.hpp"
#include "targets/wgsl/wgsl_writer.hpp"

namespace crtforge {

const std::vector<TargetInfo>& all_targets() {
    static const std::vector<TargetInfo> targets = {
        {TargetId::Spirv, "spirv", "SPIR-V 1.0 binaries (Vulkan), fragment + full-screen vertex shader"},
        {TargetId::Glsl450, "glsl450", "GLSL 4.50 core (OpenGL 4.5)"},
        {TargetId::Glsl330, "glsl330", "GLSL 3.30 core (OpenGL 3.3)"},
        {TargetId::GlslEs300, "glsles300", "GLSL ES 3.00 (OpenGL ES 3.0 / WebGL 2)"},
        {TargetId::Hlsl50, "hlsl50", "HLSL Shader Model 5.0 (Direct3D 11)"},
        {TargetId::Hlsl60, "hlsl60", "HLSL Shader Model 6.0 (Direct3D 12, DXC)"},
        {TargetId::Godot4, "godot4", "Godot 4 canvas_item .gdshader + ShaderMaterial (node and screen modes)"},
        {TargetId::Godot3, "godot3", "Godot 3 canvas_item .shader + ShaderMaterial (node and screen modes)"},
        {TargetId::Wgsl, "wgsl", "WGSL for WebGPU: one module, vs_main + fs_main (crtforge's own emitter)"},
    };
    return targets;
}

const TargetInfo* find_target(const std::string& name) {
    for (const auto& t : all_targets())
        if (name == t.name) return &t;
    return nullptr;
}

Result<const TargetInfo*> lookup_target(const std::string& name) {
    if (const TargetInfo* t = find_target(name)) return t;
    std::vector<std::string> names;
    for (const auto& t : all_targets()) names.emplace_back(t.name);
    return make_error("unknown target '" + name + "' (targets: " + join_list(names) + ")", {}, 0, "--target");
}

const TargetInfo& target_info(TargetId id) {
    for (const auto& t : all_targets())
        if (t.id == id) return t;
    return all_targets().front();
}

const std::vector<std::string>& shader_roles(TargetId id) {
    static const std::vector<std::string> stages = {"vertex", "fragment"};
    static const std::vector<std::string> godot = {"shader", "screenShader"};
    static const std::vector<std::string> module = {"shader"};
    switch (id) {
        case TargetId::Godot4:
        case TargetId::Godot3: return godot;
        case TargetId::Wgsl: return module;
        default: return stages;
    }
}

Result<TargetOutput> generate_target(TargetId id, const TargetInput& input) {
    switch (id) {
        case TargetId::Spirv: return spirv::Generate(input);
        case TargetId::Glsl450: return glsl::Generate(input, {450, false});
        case TargetId::Glsl330: return glsl::Generate(input, {330, false});
        case TargetId::GlslEs300: return glsl::Generate(input, {300, true});
        case TargetId::Hlsl50: return hlsl::Generate(input, {50});
        case TargetId::Hlsl60: return hlsl::Generate(input, {60});
        case TargetId::Godot4: return godot::Generate(input, 4);
        case TargetId::Godot3: return godot::Generate(input, 3);
        case TargetId::Wgsl: return wgsl::Generate(input);
    }
    return make_error("unknown target");
}

std::string target_fingerprint(TargetId id) {
    // Bump the suffix whenever an emitter's output changes for the same SPIR-V.
    if (id == TargetId::Wgsl) return "wgsl/crtforge-emitter/v1";
    return std::string(target_info(id).name) + "/spirv-cross-2021.01.15/v2";
}

}  // namespace crtforge
