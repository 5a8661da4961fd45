#include "targets/hlsl/hlsl_writer.hpp"

#include <regex>
#include <set>
#include <vector>

#include <fmt/format.h>
#include <spirv_cross/spirv_hlsl.hpp>

#include "crtforge/assembler.hpp"
#include "targets/cross_compile.hpp"

namespace crtforge::hlsl {

namespace {

// The locations the fragment stage reads. D3D links a vertex output to a pixel input by register,
// assigned in declaration order: an output the pixel shader does not read (the optimiser dropped
// it there, or SPIRV-Cross left out an unread one) would shift every later one, so the vertex
// stage leaves it out too.
std::set<uint32_t> fragment_input_locations(const SpirvBinary& fragment) {
    std::set<uint32_t> out;
    spirv_cross::Compiler reader(fragment);
    // The active ones: SPIRV-Cross's pixel shader declares no input the code never reads.
    for (const spirv_cross::Resource& r : reader.get_shader_resources(reader.get_active_interface_variables()).stage_inputs)
        if (reader.has_decoration(r.id, spv::DecorationLocation)) out.insert(reader.get_decoration(r.id, spv::DecorationLocation));
    return out;
}

// The vertex shader without the outputs (TEXCOORD<location>) the pixel shader does not read: their
// members of SPIRV_Cross_Output and the lines that copy them there. (This SPIRV-Cross's HLSL
// writer honours neither output masks nor interface-variable sets for stage outputs.)
std::string drop_unread_outputs(std::string text, const std::set<uint32_t>& read) {
    // "    [interpolation modifiers] type name[[N]] : TEXCOORD<location>;"
    static const std::regex member(R"(\n    (?:[A-Za-z0-9_]+ )+([A-Za-z0-9_]+)(?:\[[0-9]+\])? : TEXCOORD([0-9]+);)");
    const size_t start = text.find("struct SPIRV_Cross_Output\n{");
    if (start == std::string::npos) return text;
    const size_t end = text.find("\n};", start);
    std::vector<std::string> dropped;
    std::string body = text.substr(start, end - start), kept;
    size_t at = 0;
    for (std::sregex_iterator it(body.begin(), body.end(), member), stop; it != stop; ++it) {
        kept += body.substr(at, static_cast<size_t>(it->position()) - at);
        at = static_cast<size_t>(it->position() + it->length());
        if (read.count(static_cast<uint32_t>(std::stoul((*it)[2].str())))) kept += it->str();
        else dropped.push_back((*it)[1].str());
    }
    kept += body.substr(at);
    text.replace(start, end - start, kept);
    for (const std::string& name : dropped) {
        const std::string copy = "\n    stage_output." + name + " = " + name + ";";
        if (const size_t line = text.find(copy); line != std::string::npos) text.erase(line, copy.size());
    }
    return text;
}

}  // namespace

Result<TargetOutput> generate(const TargetInput& input, const Options& options) {
    const std::string language = fmt::format("HLSL SM {}.{}", options.shader_model / 10, options.shader_model % 10);
    std::set<uint32_t> read;
    try {
        read = fragment_input_locations(*input.fragment);
    } catch (const std::exception& e) {
        return make_validation_error(std::string("SPIRV-Cross cannot read the fragment shader's inputs: ") + e.what());
    }
    auto out = detail::emit_both_stages(input, ".vs.hlsl", ".ps.hlsl", [&](const SpirvBinary& module, ShaderStage stage) {
        auto text = detail::cross_compile<spirv_cross::CompilerHLSL>(module, stage, language, [&](spirv_cross::CompilerHLSL& c) {
            auto common = c.get_common_options();
            common.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;
            c.set_common_options(common);
            auto o = c.get_hlsl_options();
            o.shader_model = static_cast<uint32_t>(options.shader_model);
            c.set_hlsl_options(o);
        });
        if (!text.ok() || stage != ShaderStage::Vertex) return text;
        return Result<std::string>(drop_unread_outputs(std::move(text.value()), read));
    });
    if (!out.ok()) return out;
    if (input.variant->has_uniform_block()) out.value().bindings.push_back({kUniformBlockName, "cbuffer register(b0)"});
    out.value().bindings.push_back({kSourceTextureName, "Texture2D register(t1) + SamplerState _source_sampler register(s1)"});
    return out;
}

std::vector<TargetInfo> records() {
    return {
        {TargetId::Hlsl50, "hlsl50", "HLSL Shader Model 5.0 (Direct3D 11)", {"vertex", "fragment"}, "hlsl",
         [](const TargetInput& in) { return generate(in, {50}); }, "hlsl50/spirv-cross-2021.01.15/v4"},
        {TargetId::Hlsl60, "hlsl60", "HLSL Shader Model 6.0 (Direct3D 12, DXC)", {"vertex", "fragment"}, "hlsl",
         [](const TargetInput& in) { return generate(in, {60}); }, "hlsl60/spirv-cross-2021.01.15/v4"},
    };
}

}  // namespace crtforge::hlsl
