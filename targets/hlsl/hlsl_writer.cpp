#include "targets/hlsl/hlsl_writer.hpp"

#include <fmt/format.h>
#include <spirv_cross/spirv_hlsl.hpp>

#include "crtforge/assembler.hpp"
#include "targets/cross_compile.hpp"

namespace crtforge::hlsl {

Result<TargetOutput> generate(const TargetInput& input, const Options& options) {
    const std::string language = fmt::format("HLSL SM {}.{}", options.shader_model / 10, options.shader_model % 10);
    auto out = detail::emit_both_stages(input, ".vs.hlsl", ".ps.hlsl", [&](const SpirvBinary& module, ShaderStage stage) {
        return detail::cross_compile<spirv_cross::CompilerHLSL>(module, stage, language, [&](spirv_cross::CompilerHLSL& c) {
            auto common = c.get_common_options();
            common.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;
            c.set_common_options(common);
            auto o = c.get_hlsl_options();
            o.shader_model = static_cast<uint32_t>(options.shader_model);
            c.set_hlsl_options(o);
        });
    });
    if (!out.ok()) return out;
    if (input.variant->has_uniform_block()) out.value().bindings.push_back({kUniformBlockName, "cbuffer register(b0)"});
    out.value().bindings.push_back({kSourceTextureName, "Texture2D register(t1) + SamplerState _source_sampler register(s1)"});
    return out;
}

std::vector<TargetInfo> records() {
    return {
        {TargetId::Hlsl50, "hlsl50", "HLSL Shader Model 5.0 (Direct3D 11)", {"vertex", "fragment"}, "hlsl",
         [](const TargetInput& in) { return generate(in, {50}); }, "hlsl50/spirv-cross-2021.01.15/v2"},
        {TargetId::Hlsl60, "hlsl60", "HLSL Shader Model 6.0 (Direct3D 12, DXC)", {"vertex", "fragment"}, "hlsl",
         [](const TargetInput& in) { return generate(in, {60}); }, "hlsl60/spirv-cross-2021.01.15/v2"},
    };
}

}  // namespace crtforge::hlsl
