// Shared SPIRV-Cross plumbing for the GLSL and HLSL writers: one driver that builds the compiler,
// lets the writer set its options, gives resources readable names, and turns SPIRV-Cross's
// exceptions into Diagnostics.
#pragma once

#include <functional>
#include <string>

#include <spirv_cross/spirv_glsl.hpp>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "crtforge/targets.hpp"
#include "targets/float_literals.hpp"
#include "targets/spirv_flat_arrays.hpp"
#include "targets/spirv_split_io_structs.hpp"
#include "targets/spirv_gather_lowering.hpp"

namespace crtforge::detail {

// Template locals keep their names (spirv_debug_names) and GLSL allowed them, but after inlining a
// local named like a builtin (`distance`) shares main's scope with calls of it, and HLSL, Godot and
// WGSL reserve words GLSL does not (`point`, `TIME`): any name some target language reserves gets a
// trailing underscore, on every target alike; so does a local named like a uniform block member
// (a param of another stage), which Godot's plain uniforms would otherwise meet in one scope.
void rename_reserved_words(spirv_cross::Compiler& compiler);

// Renames reserved words (above) and names the uniform block instance "crt" (or `instance_name`) so members read crt.scanlineIntensity (GLSL) or
// crt_scanlineIntensity (HLSL) instead of _19.scanlineIntensity.
void apply_readable_names(spirv_cross::CompilerGLSL& compiler, const char* instance_name = nullptr);

// `<instance>.member` -> `replace(member)` everywhere in `text`: a uniform block flattened into
// plain uniforms (Godot's, WebGL 2's), its instance named `instance` so no template name matches.
std::string replace_block_access(const std::string& text, const std::string& instance,
                                 const std::function<std::string(const std::string& member)>& replace);

// Compiles `module` with a Compiler (CompilerGLSL or a subclass) after `configure(compiler)` set
// its options. `target` names the language in diagnostics ("GLSL 330", "HLSL SM 5.0"). With
// `flat_arrays`, arrays of arrays are flattened first (spirv_flat_arrays), for languages without them;
// with `lower_gathers`, textureGather becomes four reads (spirv_gather_lowering); with `split_io_structs`,
// struct stage inputs and outputs become one per member (spirv_split_io_structs): SPIRV-Cross splits
// them itself for ES but drops their `flat`, which an int member must have.
template <typename Compiler, typename Configure>
Result<std::string> cross_compile(const SpirvBinary& module, ShaderStage stage, const std::string& target,
                                  Configure&& configure, const char* instance_name = nullptr, bool flat_arrays = false,
                                  bool lower_gathers = false, bool split_io_structs = false) {
    try {
        SpirvBinary words = module;
        if (split_io_structs) split_interface_structs(words);
        if (flat_arrays) flatten_arrays_of_arrays(words);
        if (lower_gathers) lower_texture_gathers(words);
        Compiler compiler(std::move(words));
        configure(compiler);
        apply_readable_names(compiler, instance_name);
        return without_splat_selects(shorten_float_literals(compiler.compile()));
    } catch (const std::exception& e) {
        return make_validation_error("SPIRV-Cross cannot express the " + std::string(shader_stage_name(stage)) +
                                     " shader in " + target + ": " + e.what());
    }
}

// Emits the vertex then the fragment shader of `input` with `emit(module, stage)`, naming the files
// "<preset><suffix>" with the given per-stage suffixes.
template <typename Emit>
Result<TargetOutput> emit_both_stages(const TargetInput& input, const char* vertex_suffix,
                                      const char* fragment_suffix, Emit&& emit) {
    TargetOutput out;
    for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
        const SpirvBinary& module = stage == ShaderStage::Vertex ? *input.vertex : *input.fragment;
        Result<std::string> text = emit(module, stage);
        if (!text.ok()) return text.error();
        out.files.push_back({stage, stage == ShaderStage::Vertex ? vertex_suffix : fragment_suffix, std::move(text.value()), {}, {}});
    }
    return out;
}

}  // namespace crtforge::detail
