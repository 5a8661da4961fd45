// Output targets. Each target lives in targets/<lang>/ and has one entry point that turns the
// compiled SPIR-V pair of a variant into the files an engine consumes.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

enum class TargetId { Spirv, Glsl450, Glsl330, GlslEs300, WebGl2, Hlsl50, Hlsl60, Godot4, Godot3, Wgsl };

struct TargetInput;
struct TargetOutput;
struct SceneTargetInput;
struct OutputFile;

// Everything crtforge knows about one target, in one record that the exporter, the cache, the CLI
// and validation all read (no per-target switch anywhere else). Each targets/<lang>/ folder builds
// the records of its targets; targets/target_registry.cpp lists the folders.
struct TargetInfo {
    TargetId id;
    const char* name;         // CLI / manifest name: spirv, glsl450, ...
    const char* description;  // one line for `crtforge list`
    // The manifest roles of the shader files it emits, in order — one consumer compile check each:
    // vertex + fragment, Godot's node + screen shaders, or WGSL's single module.
    std::vector<std::string> shader_roles;
    // The consumer that proves the output by compiling and rendering it as the target's users do
    // (validate/consumers/: "vulkan", "gl", "gl-es", "hlsl", "godot4", "godot3", "dawn").
    const char* consumer;
    // Turns a compiled variant into the target's files.
    Result<TargetOutput> (*generate)(const TargetInput& input);
    // Names the emitter and its options in cache keys: bump it when the output for the same SPIR-V
    // changes.
    const char* fingerprint;
    // Files the target writes once per preset, beside each pass's files: a ready-made scene that
    // runs the whole pipeline (Godot's .tscn). Null: the manifest alone wires the passes.
    Result<std::vector<OutputFile>> (*generate_scene)(const SceneTargetInput& input) = nullptr;
};

const std::vector<TargetInfo>& all_targets();
const TargetInfo* find_target(const std::string& name);
// The same, or an error (field --target) that lists the targets there are.
Result<const TargetInfo*> lookup_target(const std::string& name);
const TargetInfo& target_info(TargetId id);

// One emitted file. `data` is text for source targets and raw bytes for SPIR-V.
struct OutputFile {
    ShaderStage stage;
    std::string suffix;       // appended to the preset name: ".frag.spv", ".frag", ".ps.hlsl", ...
    std::string data;
    std::string role;         // manifest key; empty: "vertex" or "fragment" from the stage
    std::string path;         // path under the target's folder; empty: "<preset><suffix>"

    std::string manifest_role() const { return !role.empty() ? role : stage == ShaderStage::Vertex ? "vertex" : "fragment"; }
    // Shader code a consumer compiles (not a material resource or a README).
    bool is_shader() const {
        const std::string r = manifest_role();
        return r == "vertex" || r == "fragment" || r == "shader" || r == "screenShader";
    }
};

// What a target gets: the variant (for names and docs) and its two SPIR-V modules.
struct TargetInput {
    const Variant* variant = nullptr;
    const SpirvBinary* fragment = nullptr;
    const SpirvBinary* vertex = nullptr;
    // The GLSL the fragment module was compiled from (with #line back to the templates), so an
    // emitter that rejects an instruction can recompile with debug lines and name the template line.
    const std::string* fragment_source = nullptr;
};

struct TargetOutput {
    std::vector<OutputFile> files;  // vertex first, then fragment
    // How the host binds resources in this target's language, for the manifest:
    // e.g. {"CrtParams", "b0"} for HLSL, {"CrtParams", "binding=0"} for GLSL 450.
    std::vector<std::pair<std::string, std::string>> bindings;
    // Extra keys for this target's manifest entry, as a JSON object ("" = none): e.g. WGSL's
    // entry points, bind-group layout and uniform-buffer byte layout.
    std::string manifest_json;
};

// What a target's scene generator gets: the preset, and per pass its variant and this target's
// files (as generate() made them, paths included), plus the LUT files the export writes.
struct SceneTargetInput {
    const Preset* preset = nullptr;
    std::vector<const Variant*> passes;
    std::vector<const TargetOutput*> outputs;
    std::map<std::string, std::string> lut_files;  // LUT name -> file bytes (PNG)
};

// target_info(id).generate(input), with the target's name on any error.
Result<TargetOutput> generate_target(TargetId id, const TargetInput& input);

}  // namespace crtforge

