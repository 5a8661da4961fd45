// Assembles a variant into GLSL 450 (Vulkan flavour) source: declarations for the uniform block and
// baked constants, the prelude, the snippets of the enabled stages only (with #line directives
// back to the template files), and a generated main() that calls the forms in pass order.
#pragma once

#include <string>

#include "crtforge/template_library.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

// Names shared by the generator, the targets and the manifest.
inline constexpr const char* kUniformBlockName = "CrtParams";
inline constexpr const char* kUniformInstanceName = "crt";
inline constexpr const char* kSourceTextureName = "source";
inline constexpr const char* kTexCoordName = "vTexCoord";
inline constexpr int kUniformBinding = 0;
inline constexpr int kTextureBinding = 1;
inline constexpr int kDescriptorSet = 0;

struct AssembledShader {
    std::string fragment;  // GLSL 450 for glslang (uses GL_GOOGLE_cpp_style_line_directive)
    std::string vertex;    // the full-screen triangle
};

// How a program form gets its baked params. A program is written for its params as uniforms,
// which are no constant expressions, and may lean on that (an array indexed by `set - 1` in the
// branch `set == 0` never takes: an error once `set` is a constant); and glslang folds a constant
// expression in double precision where a GPU computes the uniform's in 32 bits. Variables it never
// writes are what a uniform is, and spirv-opt folds them in 32 bits: a program's first choice
// (compile_variant). Constants: where a program needs them constant (an array size), and for
// crtforge's own stages.
// Specialized: the scalar ones as specialization constants (`layout(constant_id = N) const`), for
// a render from the SPIR-V alone: the optimiser runs once for every preset that shares the text
// (spirv_spec_values.hpp) and the driver folds the values when it builds the pipeline.
enum class BakedParams { Constants, Variables, Specialized };

// A snippet stage's forms run in the generated main(); a program form (FormSpec::program()) is the
// pass's whole vertex and fragment shader, after the same declarations, with only the baked
// params it names.
AssembledShader assemble(const TemplateLibrary& library, const Variant& variant, BakedParams baked = BakedParams::Constants);

// The GLSL type of a builtin's uniform member: vec2, float (time) or int (frameCount).
const char* builtin_glsl_type(Builtin builtin);

}  // namespace crtforge
