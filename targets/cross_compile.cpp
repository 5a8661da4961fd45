#include "targets/cross_compile.hpp"
#include "generator/reserved_words.hpp"

#include "crtforge/assembler.hpp"

namespace crtforge::detail {

void rename_reserved_words(spirv_cross::Compiler& compiler) {
    for (uint32_t id = 1; id < compiler.get_current_id_bound(); ++id) {
        const std::string name = compiler.get_name(id);
        if (!name.empty() && !reserving_language(name).empty()) compiler.set_name(id, name + "_");
    }
}

void apply_readable_names(spirv_cross::CompilerGLSL& compiler) {
    rename_reserved_words(compiler);
    auto resources = compiler.get_shader_resources();
    for (const auto& ub : resources.uniform_buffers) compiler.set_name(ub.id, kUniformInstanceName);
}

}  // namespace crtforge::detail
