#include "targets/cross_compile.hpp"
#include "generator/reserved_words.hpp"
#include "targets/word_scan.hpp"

#include <set>

#include "crtforge/assembler.hpp"

namespace crtforge::detail {

void rename_reserved_words(spirv_cross::Compiler& compiler) {
    // Uniform block members: plain uniforms of the same name in Godot (and the template's globals),
    // which a local of another stage's function, inlined into main, would hide.
    std::set<std::string> members;
    for (const auto& ub : compiler.get_shader_resources().uniform_buffers) {
        const auto& type = compiler.get_type(ub.base_type_id);
        for (uint32_t i = 0; i < type.member_types.size(); ++i) members.insert(compiler.get_member_name(ub.base_type_id, i));
    }
    for (uint32_t id = 1; id < compiler.get_current_id_bound(); ++id) {
        const std::string name = compiler.get_name(id);
        if (name.empty()) continue;
        if (!reserving_language(name).empty() || members.count(name)) compiler.set_name(id, name + "_");
    }
}

std::string replace_block_access(const std::string& text, const std::string& instance,
                                 const std::function<std::string(const std::string& member)>& replace) {
    return replace_member_access(text, instance, replace);
}

void apply_readable_names(spirv_cross::CompilerGLSL& compiler, const char* instance_name) {
    rename_reserved_words(compiler);
    auto resources = compiler.get_shader_resources();
    for (const auto& ub : resources.uniform_buffers) compiler.set_name(ub.id, instance_name ? instance_name : kUniformInstanceName);
}

}  // namespace crtforge::detail
