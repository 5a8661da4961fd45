// What the SPIR-V rewrites for languages with fewer types (spirv_flat_arrays,
// godot/spirv_square_matrices) read of a module before changing it: its types, its constants and
// the type of each value.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "generator/spirv_words.hpp"

namespace crtforge::detail {

struct SpirvFacts {
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> vectors;   // id -> {component type, count}
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> matrices;  // id -> {column type, columns}
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> pointers;  // id -> {storage class, pointee}
    std::map<uint32_t, std::pair<uint32_t, uint32_t>> arrays;    // id -> {element type, length constant}
    std::map<uint32_t, uint32_t> runtime_arrays;                 // id -> element type
    std::map<uint32_t, std::vector<uint32_t>> structs;           // id -> member types
    std::set<uint32_t> blocks;                                   // structs decorated Block / BufferBlock
    std::map<uint32_t, uint32_t> int_values;                     // 32-bit integer constant -> its value
    std::map<uint32_t, std::vector<uint32_t>> constant_composites;  // id -> constituents
    std::set<uint32_t> constant_nulls;
    std::map<uint32_t, uint32_t> value_types;                    // result id -> result type
    std::map<uint32_t, size_t> declared_at;                      // type id -> its declaration's first word

    uint32_t type_of(uint32_t value) const {
        auto t = value_types.find(value);
        return t == value_types.end() ? 0 : t->second;
    }
    // The element type of a sized or runtime array (0: not an array).
    uint32_t element(uint32_t array) const {
        if (auto a = arrays.find(array); a != arrays.end()) return a->second.first;
        if (auto r = runtime_arrays.find(array); r != runtime_arrays.end()) return r->second;
        return 0;
    }
};

// Whether an instruction of `opcode` can hand a pointer on (a call, a copy, a select, a phi): where
// a rewrite that retypes some pointers must refuse rather than leave a user of the old type.
bool hands_pointers_on(uint32_t opcode);

SpirvFacts gather_spirv_facts(const SpirvBinary& words, const std::vector<SpirvInstruction>& list);

}  // namespace crtforge::detail
