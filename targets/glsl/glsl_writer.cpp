#include "targets/glsl/glsl_writer.hpp"

#include <fmt/format.h>

#include "crtforge/assembler.hpp"
#include "targets/cross_compile.hpp"

namespace crtforge::glsl {

Result<TargetOutput> generate(const TargetInput& input, const Options& options) {
    const std::string language = options.es ? fmt::format("GLSL ES {}", options.version) : fmt::format("GLSL {}", options.version);
    const Precision precision = input.variant->options.precision;
    auto out = detail::emit_both_stages(input, ".vert", ".frag", [&](const SpirvBinary& module, ShaderStage stage) {
        return detail::cross_compile<spirv_cross::CompilerGLSL>(module, stage, language, [&](spirv_cross::CompilerGLSL& c) {
            auto o = c.get_common_options();
            o.version = static_cast<uint32_t>(options.version);
            o.es = options.es;
            o.vulkan_semantics = false;
            o.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;
            // ES needs a default float precision; medium-precision variants also carry
            // RelaxedPrecision decorations, which SPIRV-Cross prints as mediump.
            o.fragment.default_float_precision = precision == Precision::High
                ? spirv_cross::CompilerGLSL::Options::Highp : spirv_cross::CompilerGLSL::Options::Mediump;
            c.set_common_options(o);
        });
    });
    if (!out.ok()) return out;
    const bool explicit_bindings = options.version >= 420 && !options.es;
    if (input.variant->has_uniform_block())
        out.value().bindings.push_back({kUniformBlockName, explicit_bindings
            ? "layout(binding = 0) uniform block, std140"
            : "std140 uniform block: bind with glUniformBlockBinding(program, glGetUniformBlockIndex(program, \"CrtParams\"), 0)"});
    out.value().bindings.push_back({kSourceTextureName, explicit_bindings
        ? "layout(binding = 1) sampler2D"
        : "sampler2D: set with glUniform1i(glGetUniformLocation(program, \"source\"), unit)"});
    return out;
}

std::vector<TargetInfo> records() {
    // Bump a fingerprint whenever that target's output changes for the same SPIR-V.
    return {
        {TargetId::Glsl450, "glsl450", "GLSL 4.50 core (OpenGL 4.5)", {"vertex", "fragment"}, "gl",
         [](const TargetInput& in) { return generate(in, {450, false}); }, "glsl450/spirv-cross-2021.01.15/v2"},
        {TargetId::Glsl330, "glsl330", "GLSL 3.30 core (OpenGL 3.3)", {"vertex", "fragment"}, "gl",
         [](const TargetInput& in) { return generate(in, {330, false}); }, "glsl330/spirv-cross-2021.01.15/v2"},
        {TargetId::GlslEs300, "glsles300", "GLSL ES 3.00 (OpenGL ES 3.0 / WebGL 2)", {"vertex", "fragment"}, "gl-es",
         [](const TargetInput& in) { return generate(in, {300, true}); }, "glsles300/spirv-cross-2021.01.15/v2"},
    };
}

}  // namespace crtforge::glsl
