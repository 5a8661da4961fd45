// clamp(x, lo, hi) as min(max(x, lo), hi), before spirv-opt sees it.
//
// GLSL defines clamp as min(max(x, minVal), maxVal) and leaves it undefined when minVal > maxVal.
// Shaders in the wild do write that case (RetroArch's Advanced_CRT_shader_whkrmrgks0 has
// clamp(0.0, 1.0, t) for clamp(t, 0.0, 1.0)), and every driver computes the formula — Mesa lowers
// fclamp to fmin(fmax()). spirv-opt's constant folding instead uses a rule that holds only when
// lo <= hi (x < lo gives lo), so the same shader drew another picture once optimised (13 dB apart on
// that preset) than compiled as RetroArch compiles it. Written as the formula, the optimiser folds
// only what the formula says, and a driver's pattern matching still turns min(max()) back into its
// clamp or saturate. A clamp whose bounds are constants in order (clamp(x, 0.0, 1.0)) is well
// defined and stays as it is, so exported shaders keep reading as their templates.
#include "generator/spirv_clamp_lowering.hpp"

#include <bit>
#include <map>
#include <vector>

#include <glslang/SPIRV/GLSL.std.450.h>
#include <glslang/SPIRV/spirv.hpp>

#include "generator/spirv_words.hpp"

namespace crtforge {
namespace {

// The Max and Min of the same kind as a clamp, or {0, 0} for any other instruction.
std::pair<uint32_t, uint32_t> max_min_of(uint32_t instruction) {
    switch (instruction) {
        case GLSLstd450FClamp: return {GLSLstd450FMax, GLSLstd450FMin};
        case GLSLstd450UClamp: return {GLSLstd450UMax, GLSLstd450UMin};
        case GLSLstd450SClamp: return {GLSLstd450SMax, GLSLstd450SMin};
        case GLSLstd450NClamp: return {GLSLstd450NMax, GLSLstd450NMin};
        default: return {0, 0};
    }
}

// The module's 32-bit scalar and vector constants, as their component words, by id.
using Constants = std::map<uint32_t, std::vector<uint32_t>>;

Constants gather_constants(const SpirvBinary& words, const std::vector<detail::SpirvInstruction>& list) {
    std::map<uint32_t, bool> scalar_types;  // 32-bit float and integer types
    Constants out;
    for (const detail::SpirvInstruction& in : list) {
        const size_t a = in.offset;
        if ((in.opcode == spv::OpTypeFloat || in.opcode == spv::OpTypeInt) && in.count >= 3 && words[a + 2] == 32)
            scalar_types[words[a + 1]] = true;
        else if (in.opcode == spv::OpConstant && in.count == 4 && scalar_types.count(words[a + 1]))
            out[words[a + 2]] = {words[a + 3]};
        // glslang smears a scalar bound of a vector clamp (clamp(v, 0.0, 1.0)) with a composite
        // construct in the function: constant all the same.
        else if ((in.opcode == spv::OpConstantComposite || in.opcode == spv::OpCompositeConstruct) && in.count >= 4) {
            std::vector<uint32_t> parts;
            for (size_t w = a + 3; w < a + in.count; ++w) {
                auto part = out.find(words[w]);
                if (part == out.end() || part->second.size() != 1) {
                    parts.clear();
                    break;
                }
                parts.push_back(part->second.front());
            }
            if (!parts.empty()) out[words[a + 2]] = std::move(parts);
        }
    }
    return out;
}

// Whether lo <= hi in every component, both known constants, compared as the clamp's kind does.
bool ordered(const Constants& constants, uint32_t instruction, uint32_t lo_id, uint32_t hi_id) {
    auto lo = constants.find(lo_id), hi = constants.find(hi_id);
    if (lo == constants.end() || hi == constants.end() || lo->second.size() != hi->second.size()) return false;
    for (size_t i = 0; i < lo->second.size(); ++i) {
        const uint32_t l = lo->second[i], h = hi->second[i];
        const bool in_order = instruction == GLSLstd450UClamp   ? l <= h
                              : instruction == GLSLstd450SClamp ? std::bit_cast<int32_t>(l) <= std::bit_cast<int32_t>(h)
                                                                : std::bit_cast<float>(l) <= std::bit_cast<float>(h);  // false for NaN
        if (!in_order) return false;
    }
    return true;
}

}  // namespace

size_t lower_clamps(SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords || words[0] != spv::MagicNumber) return 0;
    const auto parsed = detail::spirv_instructions(words);
    if (!parsed) return 0;
    uint32_t glsl_set = 0;
    for (const detail::SpirvInstruction& in : *parsed)
        if (in.opcode == spv::OpExtInstImport && in.count >= 3 &&
            detail::spirv_literal_string(words, in.offset + 2, in.offset + in.count) == "GLSL.std.450")
            glsl_set = words[in.offset + 1];
    if (glsl_set == 0) return 0;
    const Constants constants = gather_constants(words, *parsed);

    return detail::rewrite_instructions(words, *parsed, [&](const detail::SpirvInstruction& in, SpirvBinary& out, uint32_t& bound) {
        const size_t a = in.offset;
        // OpExtInst type result set instruction x lo hi
        if (in.opcode != spv::OpExtInst || in.count != 8 || words[a + 3] != glsl_set) return false;
        const auto [max, min] = max_min_of(words[a + 4]);
        if (max == 0 || ordered(constants, words[a + 4], words[a + 6], words[a + 7])) return false;
        const uint32_t type = words[a + 1], result = words[a + 2], x = words[a + 5], lo = words[a + 6], hi = words[a + 7];
        const uint32_t raised = bound++;
        out.insert(out.end(), {(7u << 16) | spv::OpExtInst, type, raised, glsl_set, max, x, lo});
        out.insert(out.end(), {(7u << 16) | spv::OpExtInst, type, result, glsl_set, min, raised, hi});
        return true;
    });
}

}  // namespace crtforge
