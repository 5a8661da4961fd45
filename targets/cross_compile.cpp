#include "targets/cross_compile.hpp"

#include "crtforge/assembler.hpp"

namespace crtforge::detail {

void apply_readable_names(spirv_cross::CompilerGLSL& compiler) {
    auto resources = compiler.get_shader_resources();
    for (const auto& ub : resources.uniform_buffers) compiler.set_name(ub.id, kUniformInstanceName);
}

}  // namespace crtforge::detail
