#include "targets/glsl/glsl_writer.hpp"

#include <fmt/format.h>

#include "crtforge/assembler.hpp"
#include "targets/cross_compile.hpp"

namespace crtforge::glsl {

namespace {

Result<std::string> emit(const SpirvBinary& module, ShaderStage stage, const Options& options,
                         Precision precision) {
    try {
        spirv_cross::CompilerGLSL compiler(module);
        auto o = compiler.get_common_options();
        o.version = static_cast<uint32_t>(options.version);
        o.es = options.es;
        o.vulkan_semantics = false;
        o.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;
        // ES needs a default float precision; medium-precision variants also carry
        // RelaxedPrecision decorations, which SPIRV-Cross prints as mediump.
        o.fragment.default_float_precision = precision == Precision::High
            ? spirv_cross::CompilerGLSL::Options::Highp : spirv_cross::CompilerGLSL::Options::Mediump;
        compiler.set_common_options(o);
        detail::apply_readable_names(compiler);
        const std::string target = options.es ? fmt::format("GLSL ES {}", options.version)
                                               : fmt::format("GLSL {}", options.version);
        return detail::cross_compile(compiler, target.c_str(), stage);
    } catch (const std::exception& e) {
        return make_error(std::string("SPIRV-Cross rejected the module: ") + e.what());
    }
}

}  // namespace

Result<TargetOutput> Generate(const TargetInput& input, const Options& options) {
    TargetOutput out;
    for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
        const SpirvBinary& module = stage == ShaderStage::Vertex ? *input.vertex : *input.fragment;
        auto text = emit(module, stage, options, input.variant->options.precision);
        if (!text.ok()) return text.error();
        out.files.push_back({stage, stage == ShaderStage::Vertex ? ".vert" : ".frag", std::move(text.value())});
    }
    const bool explicit_bindings = options.version >= 420 && !options.es;
    if (input.variant->has_uniform_block())
        out.bindings.push_back({kUniformBlockName, explicit_bindings
            ? "layout(binding = 0) uniform block, std140"
            : "std140 uniform block: bind with glUniformBlockBinding(program, glGetUniformBlockIndex(program, \"CrtParams\"), 0)"});
    out.bindings.push_back({kSourceTextureName, explicit_bindings
        ? "layout(binding = 1) sampler2D"
        : "sampler2D: set with glUniform1i(glGetUniformLocation(program, \"source\"), unit)"});
    return out;
}

}  // namespace crtforge::glsl
