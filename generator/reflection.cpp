// Uniform-block and texture reflection through SPIRV-Cross, plus a small word walker for names and
// sample instructions (used by the "disabled stage is absent" checks).
#include "crtforge/reflection.hpp"

#include <spirv_cross/spirv_cross.hpp>

#include "generator/spirv_words.hpp"

namespace crtforge {

namespace {

std::string type_name(const spirv_cross::SPIRType& t) {
    std::string scalar;
    switch (t.basetype) {
        case spirv_cross::SPIRType::Float: scalar = "float"; break;
        case spirv_cross::SPIRType::Int: scalar = "int"; break;
        case spirv_cross::SPIRType::UInt: scalar = "uint"; break;
        case spirv_cross::SPIRType::Boolean: scalar = "bool"; break;
        default: scalar = "other"; break;
    }
    if (t.columns > 1) return "mat" + std::to_string(t.columns);
    if (t.vecsize == 1) return scalar;
    const char* prefix = scalar == "float" ? "vec" : scalar == "int" ? "ivec" : scalar == "uint" ? "uvec" : "bvec";
    return prefix + std::to_string(t.vecsize);
}

}  // namespace

Result<Reflection> reflect(const SpirvBinary& binary) {
    if (binary.size() < 5 || binary[0] != 0x07230203u) return make_error("not a SPIR-V module");
    Reflection out;
    try {
        spirv_cross::Compiler compiler(binary);
        auto resources = compiler.get_shader_resources();
        for (const auto& ub : resources.uniform_buffers) {
            ReflectedBlock block;
            block.name = compiler.get_name(ub.base_type_id);
            block.set = compiler.get_decoration(ub.id, spv::DecorationDescriptorSet);
            block.binding = compiler.get_decoration(ub.id, spv::DecorationBinding);
            const auto& type = compiler.get_type(ub.base_type_id);
            block.size = static_cast<uint32_t>(compiler.get_declared_struct_size(type));
            for (uint32_t i = 0; i < type.member_types.size(); ++i) {
                ReflectedMember m;
                m.name = compiler.get_member_name(ub.base_type_id, i);
                const spirv_cross::SPIRType& member_type = compiler.get_type(type.member_types[i]);
                m.type = type_name(member_type);
                using Base = spirv_cross::SPIRType::BaseType;
                m.scalar = member_type.basetype == Base::Float ? ReflectedMember::Scalar::Float
                         : member_type.basetype == Base::Int ? ReflectedMember::Scalar::Int
                         : member_type.basetype == Base::UInt ? ReflectedMember::Scalar::Uint
                         : member_type.basetype == Base::Boolean ? ReflectedMember::Scalar::Bool : ReflectedMember::Scalar::Other;
                m.components = member_type.vecsize;
                m.columns = member_type.columns;
                m.offset = compiler.type_struct_member_offset(type, i);
                m.size = static_cast<uint32_t>(compiler.get_declared_struct_member_size(type, i));
                block.members.push_back(m);
            }
            out.uniform_blocks.push_back(std::move(block));
        }
        for (const auto& img : resources.sampled_images) {
            ReflectedTexture t;
            t.name = compiler.get_name(img.id);
            t.set = compiler.get_decoration(img.id, spv::DecorationDescriptorSet);
            t.binding = compiler.get_decoration(img.id, spv::DecorationBinding);
            out.textures.push_back(t);
        }
    } catch (const std::exception& e) {
        return make_error(std::string("SPIR-V reflection failed: ") + e.what());
    }

    // Walk instructions: OpName (5), OpMemberName (6), image sampling/fetch/gather (87..96).
    const auto instructions = detail::spirv_instructions(binary);
    if (!instructions) return make_error("malformed SPIR-V instruction stream");
    for (const detail::SpirvInstruction& in : *instructions) {
        const size_t w = in.offset, end = in.offset + in.count;
        if (in.opcode == 5) out.names.push_back(detail::spirv_literal_string(binary, w + 2, end));
        if (in.opcode == 6) out.names.push_back(detail::spirv_literal_string(binary, w + 3, end));
        if (in.opcode >= 87 && in.opcode <= 96) ++out.texture_samples;
    }
    return out;
}

}  // namespace crtforge
