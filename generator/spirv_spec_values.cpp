#include "generator/spirv_spec_values.hpp"

#include <algorithm>
#include <bit>

#include <glslang/SPIRV/spirv.hpp>

#include "generator/spirv_words.hpp"

namespace crtforge {

namespace {

bool is_spec_scalar(uint16_t opcode) {
    return opcode == spv::OpSpecConstant || opcode == spv::OpSpecConstantTrue || opcode == spv::OpSpecConstantFalse;
}

// SpecId by result id, from the module's OpDecorate instructions.
std::map<uint32_t, uint32_t> spec_ids(const SpirvBinary& module, const std::vector<detail::SpirvInstruction>& list) {
    std::map<uint32_t, uint32_t> out;
    for (const detail::SpirvInstruction& in : list)
        if (in.opcode == spv::OpDecorate && in.count == 4 && module[in.offset + 2] == spv::DecorationSpecId)
            out[module[in.offset + 1]] = module[in.offset + 3];
    return out;
}

// Calls `visit(instruction, spec id)` for each scalar specialization constant with a SpecId;
// `visit` may change the instruction's words in place (never its length). False when `module`
// cannot be read as instructions.
template <typename Module, typename Visit>
bool for_each_spec_constant(Module& module, Visit&& visit) {
    auto list = detail::spirv_instructions(module);
    if (!list) return false;
    const auto ids = spec_ids(module, *list);
    if (ids.empty()) return true;
    for (const detail::SpirvInstruction& in : *list) {
        if (!is_spec_scalar(in.opcode) || in.count < 3) continue;
        auto id = ids.find(module[in.offset + 2]);
        if (id != ids.end()) visit(in, id->second);
    }
    return true;
}

}  // namespace

std::map<uint32_t, SpecValue> spec_constant_values(const SpirvBinary& module) {
    std::map<uint32_t, SpecValue> out;
    for_each_spec_constant(module, [&](const detail::SpirvInstruction& in, uint32_t spec_id) {
        SpecValue& value = out[spec_id];
        value.opcode = in.opcode;
        value.words.assign(module.begin() + static_cast<std::ptrdiff_t>(in.offset + 3),
                           module.begin() + static_cast<std::ptrdiff_t>(in.offset + in.count));
    });
    return out;
}

bool write_spec_constant_values(SpirvBinary& module, const std::map<uint32_t, SpecValue>& values) {
    return for_each_spec_constant(module, [&](const detail::SpirvInstruction& in, uint32_t spec_id) {
        auto value = values.find(spec_id);
        if (value == values.end()) return;
        const bool boolean = in.opcode != spv::OpSpecConstant;
        // The same SpecId is the same declaration: a type that changed is not this module's value.
        if (boolean != (value->second.opcode != spv::OpSpecConstant)) return;
        if (boolean) {
            module[in.offset] = (module[in.offset] & 0xffff0000u) | value->second.opcode;
        } else if (value->second.words.size() == in.count - 3u) {
            std::copy(value->second.words.begin(), value->second.words.end(), module.begin() + static_cast<std::ptrdiff_t>(in.offset + 3));
        }
    });
}

bool clear_spec_constant_values(SpirvBinary& module) {
    return for_each_spec_constant(module, [&](const detail::SpirvInstruction& in, uint32_t) {
        if (in.opcode == spv::OpSpecConstant)
            std::fill(module.begin() + static_cast<std::ptrdiff_t>(in.offset + 3), module.begin() + static_cast<std::ptrdiff_t>(in.offset + in.count), 0u);
        else
            module[in.offset] = (module[in.offset] & 0xffff0000u) | spv::OpSpecConstantFalse;
    });
}

SpecValue float_spec_value(float value) { return SpecValue{static_cast<uint16_t>(spv::OpSpecConstant), {std::bit_cast<uint32_t>(value)}}; }

}  // namespace crtforge
