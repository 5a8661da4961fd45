// Shared SPIRV-Cross plumbing for the GLSL and HLSL writers: readable resource names and
// exceptions turned into Diagnostics.
#pragma once

#include <functional>
#include <string>

#include <spirv_cross/spirv_glsl.hpp>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spirv_compiler.hpp"

namespace crtforge::detail {

// Names the uniform block instance "crt" so members read crt.scanlineIntensity (GLSL) or
// crt_scanlineIntensity (HLSL) instead of _19.scanlineIntensity.
void apply_readable_names(spirv_cross::CompilerGLSL& compiler);

// Runs compile() and converts SPIRV-Cross exceptions into a Diagnostic naming target and stage.
Result<std::string> cross_compile(spirv_cross::CompilerGLSL& compiler, const char* target, ShaderStage stage);

}  // namespace crtforge::detail
