// Compiling and linking a GLSL vertex + fragment pair with the GL driver, and binding the linked
// program's interface by name: the uniform block to uniform-buffer binding 0 and the samplers to
// their texture units (the input's to unit 0), whatever layout(binding = ...) the source carries
// (GLSL 330 output only has them under GL_ARB_shading_language_420pack, GLSL ES 300 never).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/gl_engine.hpp"
#include "runtime/gl/gl_functions.hpp"
#include "runtime/gl/gl_objects.hpp"

namespace crtforge::gl {

// A compile failure is ErrorKind::Validation, "GL driver rejected the <vertex|fragment> shader: "
// plus the first line of the driver's info log; a link failure the same with "the program at
// link". Needs the context current.
Result<UniqueProgram> build_program(const GlFunctions& gl, const std::string& vertex_source,
                                    const std::string& fragment_source);

// The first non-blank line of a driver info log, trimmed ("(empty info log)" if there is none).
std::string first_log_line(const std::string& log);

struct ProgramBindings {
    // The active uniform block, bound to binding 0; absent when the program has none (the
    // compiler may drop an unused one).
    struct Block {
        size_t data_size = 0;  // GL_UNIFORM_BLOCK_DATA_SIZE: std140 rounds it up to 16 bytes
        size_t used_size = 0;  // where its last active member ends (= data_size if unknown)
    };
    std::optional<Block> uniform_block;
    bool samples_texture = false;  // the first sampler (the job's input) is active (location != -1)
};

// A sampler2D uniform and the texture unit it reads.
struct SamplerUnit {
    std::string name;  // "" = none (nothing is bound)
    GLint unit = 0;
};

// Binds the block named `uniform_block` and each of `samplers` to its unit (program in use after
// the call); a sampler the program does not use is skipped. Any other active uniform block is an
// Input error: the job cannot feed it.
Result<ProgramBindings> bind_program_interface(const GlFunctions& gl, GLuint program, const std::string& uniform_block,
                                               const std::vector<SamplerUnit>& samplers);

// Sets each of `uniforms` on the program in use; an active plain uniform of the program that is
// neither among them nor a sampler is an Input error (it would silently read 0).
Status set_plain_uniforms(const GlFunctions& gl, GLuint program, const std::vector<PlainUniform>& uniforms);

}  // namespace crtforge::gl
