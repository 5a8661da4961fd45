#include "targets/hlsl/hlsl_writer.hpp"

#include <fmt/format.h>
#include <spirv_cross/spirv_hlsl.hpp>

#include "crtforge/assembler.hpp"
#include "targets/cross_compile.hpp"

namespace crtforge::hlsl {

namespace {

Result<std::string> emit(const SpirvBinary& module, ShaderStage stage, const Options& options) {
    try {
        spirv_cross::CompilerHLSL compiler(module);
        auto common = compiler.get_common_options();
        common.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;
        compiler.set_common_options(common);
        auto o = compiler.get_hlsl_options();
        o.shader_model = static_cast<uint32_t>(options.shader_model);
        compiler.set_hlsl_options(o);
        detail::apply_readable_names(compiler);
        const std::string target = fmt::format("HLSL SM {}.{}", options.shader_model / 10, options.shader_model % 10);
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
        auto text = emit(module, stage, options);
        if (!text.ok()) return text.error();
        out.files.push_back({stage, stage == ShaderStage::Vertex ? ".vs.hlsl" : ".ps.hlsl", std::move(text.value())});
    }
    if (input.variant->has_uniform_block()) out.bindings.push_back({kUniformBlockName, "cbuffer register(b0)"});
    out.bindings.push_back({kSourceTextureName, "Texture2D register(t1) + SamplerState _source_sampler register(s1)"});
    return out;
}

}  // namespace crtforge::hlsl
