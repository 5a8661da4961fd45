// A SPIR-V module as words: its instructions in order, its literal strings, and the rewrite every
// SPIR-V pass of crtforge's own builds on (names, clamps, powers, gathers, matrices, arrays), which
// must rewrite words rather than read a model of the module.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "crtforge/spirv_compiler.hpp"

namespace crtforge::detail {

inline constexpr size_t kSpirvHeaderWords = 5;

struct SpirvInstruction {
    size_t offset = 0;    // its first word
    uint16_t count = 0;   // its words, the opcode word included
    uint16_t opcode = 0;
};

// The instructions after the header, in order; nothing when a word count is 0 or runs past the end.
inline std::optional<std::vector<SpirvInstruction>> spirv_instructions(const SpirvBinary& words) {
    std::vector<SpirvInstruction> out;
    for (size_t at = kSpirvHeaderWords; at < words.size();) {
        const auto count = static_cast<uint16_t>(words[at] >> 16);
        if (count == 0 || at + count > words.size()) return std::nullopt;
        out.push_back({at, count, static_cast<uint16_t>(words[at] & 0xffffu)});
        at += count;
    }
    return out;
}

// The literal string operand in words [first, end): nul-terminated, packed little-endian.
inline std::string spirv_literal_string(const SpirvBinary& words, size_t first, size_t end) {
    std::string out;
    for (size_t w = first; w < end; ++w)
        for (int b = 0; b < 4; ++b) {
            const char c = static_cast<char>((words[w] >> (8 * b)) & 0xffu);
            if (c == '\0') return out;
            out += c;
        }
    return out;
}

// Appends the instruction `opcode` with `operands` (its result type and id among them) to `out`.
inline void append_instruction(SpirvBinary& out, uint32_t opcode, std::span<const uint32_t> operands) {
    out.push_back((static_cast<uint32_t>(operands.size() + 1) << 16) | (opcode & 0xffffu));
    out.insert(out.end(), operands.begin(), operands.end());
}
inline void append_instruction(SpirvBinary& out, uint32_t opcode, std::initializer_list<uint32_t> operands) {
    append_instruction(out, opcode, std::span<const uint32_t>(operands.begin(), operands.size()));
}

// Appends `in`, an instruction of `words`, to `out` as it is.
inline void append_copy(SpirvBinary& out, const SpirvBinary& words, const SpirvInstruction& in) {
    out.insert(out.end(), words.begin() + static_cast<std::ptrdiff_t>(in.offset),
               words.begin() + static_cast<std::ptrdiff_t>(in.offset + in.count));
}

// The module rewritten instruction by instruction: `rewrite(in, out, bound)` either appends the
// instructions that replace `in` to `out` (taking new ids from `bound`) and returns true, or
// returns false to keep `in` as it is. Returns how many it replaced; with none, `words` is left
// untouched. The id bound in the header is updated.
template <typename Rewrite>
size_t rewrite_instructions(SpirvBinary& words, const std::vector<SpirvInstruction>& list, Rewrite&& rewrite) {
    SpirvBinary out(words.begin(), words.begin() + kSpirvHeaderWords);
    out.reserve(words.size() + 16);
    uint32_t bound = words[3];
    size_t rewritten = 0;
    for (const SpirvInstruction& in : list) {
        if (rewrite(in, out, bound)) {
            ++rewritten;
            continue;
        }
        append_copy(out, words, in);
    }
    if (rewritten == 0) return 0;
    out[3] = bound;
    words = std::move(out);
    return rewritten;
}

}  // namespace crtforge::detail
