// The values of a module's specialization constants, by SpecId. A pass whose baked params are
// specialization constants (BakedParams::Specialized) is optimised once for every preset that
// shares its text: the optimiser's memo keys the module with these values cleared, and the
// preset's own values are written back into the optimised module (spirv-opt keeps each constant
// and its SpecId; it folds none of them, as a driver may still replace them).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "crtforge/spirv_compiler.hpp"

namespace crtforge {

struct SpecValue {
    uint16_t opcode = 0;           // OpSpecConstant, OpSpecConstantTrue or OpSpecConstantFalse
    std::vector<uint32_t> words;   // OpSpecConstant's literal words
};

// Every OpSpecConstant / OpSpecConstantTrue / OpSpecConstantFalse that carries a SpecId.
std::map<uint32_t, SpecValue> spec_constant_values(const SpirvBinary& module);

// Sets each SpecId's constant to `values`' (ids the module no longer holds are skipped): with
// `clear`, to 0 / false instead. Returns false when the module cannot be read as instructions.
bool write_spec_constant_values(SpirvBinary& module, const std::map<uint32_t, SpecValue>& values);
bool clear_spec_constant_values(SpirvBinary& module);

// A float specialization constant's value, as glslang writes `layout(constant_id = N) const float x = v;`.
SpecValue float_spec_value(float value);

}  // namespace crtforge
