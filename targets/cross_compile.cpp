#include "targets/cross_compile.hpp"

#include "crtforge/assembler.hpp"

namespace crtforge::detail {

void apply_readable_names(spirv_cross::CompilerGLSL& compiler) {
    auto resources = compiler.get_shader_resources();
    for (const auto& ub : resources.uniform_buffers) compiler.set_name(ub.id, kUniformInstanceName);
}

Result<std::string> cross_compile(spirv_cross::CompilerGLSL& compiler, const char* target, ShaderStage stage) {
    try {
        return compiler.compile();
    } catch (const std::exception& e) {
        return make_validation_error(std::string("SPIRV-Cross cannot express the ") + shader_stage_name(stage) +
                          " shader in " + target + ": " + e.what());
    }
}

}  // namespace crtforge::detail
