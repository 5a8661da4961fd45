// GLSL/HLSL -> SPIR-V with glslang as a library, then SPIRV-Tools optimisation and validation.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"

namespace crtforge {

using SpirvBinary = std::vector<uint32_t>;

enum class ShaderStage { Vertex, Fragment };
const char* shader_stage_name(ShaderStage stage);  // "vert" / "frag"

enum class SourceLanguage { Glsl, Hlsl };

struct CompileOptions {
    ShaderStage stage = ShaderStage::Fragment;
    SourceLanguage language = SourceLanguage::Glsl;
    bool optimize = true;            // SPIRV-Tools performance passes (folds baked constants)
    std::string entry_point = "main";
    std::string source_name;         // used in diagnostics when the source has no #line
    bool debug_lines = false;        // keep OpLine (template file:line) on instructions, for diagnostics
    bool local_names = true;         // SSA values keep their template local's name (spirv_debug_names)
};

// Compiles one shader. Errors carry the template file:line recovered from #line directives.
// Every module that comes out has passed spirv-val.
Result<SpirvBinary> compile_to_spirv(const std::string& source, const CompileOptions& options);

// glslang's preprocessor alone on Vulkan GLSL (as for SPIR-V: VULKAN is defined; a source without
// #version is 450): macros expanded, inactive #if branches and comments blanked, every line kept
// where it was and #line directives kept. Errors (#error, a malformed directive) carry file:line.
Result<std::string> preprocess_vulkan_glsl(const std::string& source, ShaderStage stage, const std::string& name);

// spirv-val on a module (Vulkan 1.0 environment). Modules found valid are remembered (a bounded
// process memo, compared word for word), so the same bytes are checked once.
Status validate_spirv(const SpirvBinary& binary);

// Text form, for debugging and tests.
std::string disassemble_spirv(const SpirvBinary& binary);

// Re-parses GLSL/HLSL text as a consumer would (no SPIR-V kept): used to prove target outputs.
// `version`/`es` select the GLSL dialect; for HLSL `entry_point` is the function to compile.
Status check_glsl(const std::string& source, ShaderStage stage, int version, bool es);
Status check_hlsl(const std::string& source, ShaderStage stage, const std::string& entry_point);

// Versions of the compiler libraries, folded into cache keys.
std::string compiler_versions();

}  // namespace crtforge
