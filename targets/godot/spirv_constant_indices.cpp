// Godot 3 indexes a vector or a matrix by integer constants only ("Only integer constants are
// allowed as index at the moment"). RetroArch's shaders index them by loop counters
// (`for (int i = 0; i < 3; ++i) c[i] = texture(..., pow(s[i], g))...`: crt-yo6's per-channel
// reads, mame_hlsl's chroma matrix): spirv-opt unrolls such a loop fully once it is marked for
// unrolling, and the counter's indices become constants. Only a module with such an index is
// unrolled, so the other Godot 3 shaders keep their loops.
#include "targets/godot/spirv_constant_indices.hpp"

#include <spirv-tools/optimizer.hpp>
#include <spirv_cross/spirv.hpp>

#include "targets/spirv_facts.hpp"

namespace crtforge::godot {

bool has_variable_vector_index(const SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords) return false;
    const auto list = detail::spirv_instructions(words);
    if (!list) return false;
    const detail::SpirvFacts f = detail::gather_spirv_facts(words, *list);
    for (const detail::SpirvInstruction& in : *list) {
        const size_t a = in.offset;
        if (in.opcode == spv::OpVectorExtractDynamic || in.opcode == spv::OpVectorInsertDynamic) return true;
        if ((in.opcode != spv::OpAccessChain && in.opcode != spv::OpInBoundsAccessChain) || in.count < 5) continue;
        auto pointer = f.pointers.find(f.type_of(words[a + 3]));
        if (pointer == f.pointers.end()) continue;
        uint32_t type = pointer->second.second;
        for (size_t i = a + 4; i < a + in.count && type != 0; ++i) {
            const bool constant = f.int_values.count(words[i]) != 0;
            if (auto v = f.vectors.find(type); v != f.vectors.end()) {
                if (!constant) return true;
                type = v->second.first;
            } else if (auto m = f.matrices.find(type); m != f.matrices.end()) {
                if (!constant) return true;
                type = m->second.first;
            } else if (auto s = f.structs.find(type); s != f.structs.end()) {
                const uint32_t member = constant ? f.int_values.at(words[i]) : UINT32_MAX;
                type = member < s->second.size() ? s->second[member] : 0;
            } else {
                type = f.element(type);
            }
        }
    }
    return false;
}

bool with_loops_unrolled_for_constant_indices(SpirvBinary& words) {
    if (!has_variable_vector_index(words)) return false;
    SpirvBinary marked = words;
    const auto list = detail::spirv_instructions(marked);
    if (!list) return false;
    for (const detail::SpirvInstruction& in : *list)
        if (in.opcode == spv::OpLoopMerge && in.count >= 4) {
            uint32_t& control = marked[in.offset + 3];
            control = (control & ~static_cast<uint32_t>(spv::LoopControlDontUnrollMask)) | spv::LoopControlUnrollMask;
        }
    spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_0);
    optimizer.SetMessageConsumer([](spv_message_level_t, const char*, const spv_position_t&, const char*) {});
    optimizer.RegisterPass(spvtools::CreateLoopUnrollPass(/*fully_unroll*/ true))
        .RegisterPass(spvtools::CreateLocalAccessChainConvertPass())
        .RegisterPass(spvtools::CreateLocalSingleStoreElimPass())
        .RegisterPass(spvtools::CreateSSARewritePass())
        .RegisterPass(spvtools::CreateCCPPass())
        .RegisterPass(spvtools::CreateSimplificationPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass())
        .RegisterPass(spvtools::CreateBlockMergePass());
    SpirvBinary unrolled;
    if (!optimizer.Run(marked.data(), marked.size(), &unrolled)) return false;
    words = std::move(unrolled);
    return true;
}

}  // namespace crtforge::godot
