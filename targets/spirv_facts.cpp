#include "targets/spirv_facts.hpp"

#include <spirv_cross/spirv.hpp>

namespace crtforge::detail {

bool hands_pointers_on(uint32_t opcode) {
    switch (static_cast<spv::Op>(opcode)) {
        case spv::OpFunctionCall:
        case spv::OpCopyObject:
        case spv::OpCopyMemory:
        case spv::OpCopyMemorySized:
        case spv::OpSelect:
        case spv::OpPhi: return true;
        default: return false;
    }
}

SpirvFacts gather_spirv_facts(const SpirvBinary& w, const std::vector<SpirvInstruction>& list) {
    SpirvFacts f;
    std::set<uint32_t> int_types;
    for (const SpirvInstruction& in : list) {
        const size_t a = in.offset;
        const auto op = static_cast<spv::Op>(in.opcode);
        auto at = [&](size_t i) { return i < in.count ? w[a + i] : 0u; };
        auto rest = [&](size_t from) {
            return std::vector<uint32_t>(w.begin() + static_cast<long>(a + from), w.begin() + static_cast<long>(a + in.count));
        };
        switch (op) {
            case spv::OpTypeInt: if (at(2) == 32) int_types.insert(at(1)); break;
            case spv::OpTypeVector: f.vectors[at(1)] = {at(2), at(3)}; break;
            case spv::OpTypeMatrix: f.matrices[at(1)] = {at(2), at(3)}; break;
            case spv::OpTypePointer: f.pointers[at(1)] = {at(2), at(3)}; break;
            case spv::OpTypeArray: f.arrays[at(1)] = {at(2), at(3)}; break;
            case spv::OpTypeRuntimeArray: f.runtime_arrays[at(1)] = at(2); break;
            case spv::OpTypeStruct: f.structs[at(1)] = rest(2); break;
            case spv::OpDecorate:
                if (at(2) == spv::DecorationBlock || at(2) == spv::DecorationBufferBlock) f.blocks.insert(at(1));
                break;
            case spv::OpConstant:
                if (int_types.count(at(1)) && in.count == 4) f.int_values[at(2)] = at(3);
                break;
            case spv::OpConstantComposite: f.constant_composites[at(2)] = rest(3); break;
            case spv::OpConstantNull: f.constant_nulls.insert(at(2)); break;
            default: break;
        }
        if (op >= spv::OpTypeVoid && op <= spv::OpTypeForwardPointer && in.count >= 2) f.declared_at[at(1)] = a;
        bool has_result = false, has_type = false;
        spv::HasResultAndType(op, &has_result, &has_type);
        if (has_result && has_type && in.count >= 3) f.value_types[at(2)] = at(1);
    }
    return f;
}

}  // namespace crtforge::detail
