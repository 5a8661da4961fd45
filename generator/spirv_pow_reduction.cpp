// pow(x, c) for a constant c, as the square roots and products it equals.
//
// Templates keep each document's formula term for term, so pow(scanline, scanlineSharpness) stays
// pow in the source; a preset that fixes scanlineSharpness = 1.5 makes the exponent a constant after
// spirv-opt, and nothing in SPIRV-Tools or the drivers' compilers rewrites it (LLVM only does so
// under fast-math, and Mesa's gallivm expands pow to log2, multiply, exp2: two polynomial
// evaluations). x * sqrt(x) is one square root and one product on every GPU, and closer to the exact
// value than exp2(1.5 * log2(x)). For x < 0, where GLSL leaves pow undefined, the integer powers give
// the product (x * x * x for 3: what the double-precision reference's std::pow gives, and what
// drivers that expand constant powers give; Mesa's exp2(3 * log2(x)) gives NaN) and the half powers
// NaN, as pow does.
#include "generator/spirv_pow_reduction.hpp"

#include <bit>
#include <map>
#include <optional>
#include <set>
#include <string>

#include <glslang/SPIRV/GLSL.std.450.h>
#include <glslang/SPIRV/spirv.hpp>

#include "generator/spirv_words.hpp"

namespace crtforge {
namespace {

using Instruction = detail::SpirvInstruction;

// What the module says about its float constants: each scalar or uniform vector constant's value.
struct ConstantFacts {
    uint32_t glsl_set = 0;
    std::map<uint32_t, float> values;
};

ConstantFacts gather(const SpirvBinary& words, const std::vector<Instruction>& list) {
    ConstantFacts facts;
    std::set<uint32_t> float32_types;  // scalar and vector types of 32-bit floats
    for (const Instruction& in : list) {
        const size_t a = in.offset;
        switch (in.opcode) {
            case spv::OpExtInstImport:
                if (in.count >= 3 && detail::spirv_literal_string(words, a + 2, a + in.count) == "GLSL.std.450")
                    facts.glsl_set = words[a + 1];
                break;
            case spv::OpTypeFloat:
                if (in.count == 3 && words[a + 2] == 32) float32_types.insert(words[a + 1]);
                break;
            case spv::OpTypeVector:
                if (in.count == 4 && float32_types.count(words[a + 2])) float32_types.insert(words[a + 1]);
                break;
            case spv::OpConstant:
                if (in.count == 4 && float32_types.count(words[a + 1]))
                    facts.values[words[a + 2]] = std::bit_cast<float>(words[a + 3]);
                break;
            case spv::OpConstantComposite: {
                if (in.count < 4 || !float32_types.count(words[a + 1])) break;
                std::optional<float> same;
                for (size_t w = a + 3; w < a + in.count; ++w) {
                    auto part = facts.values.find(words[w]);
                    if (part == facts.values.end() || (same && std::bit_cast<uint32_t>(*same) != std::bit_cast<uint32_t>(part->second))) {
                        same.reset();
                        break;
                    }
                    same = part->second;
                }
                if (same) facts.values[words[a + 2]] = *same;
                break;
            }
            default: break;
        }
    }
    return facts;
}

// Writes the instructions that compute pow(x, exponent) into `result`, or returns false when the
// exponent is not one of the reduced ones.
class PowWriter {
public:
    PowWriter(SpirvBinary& out, uint32_t glsl_set, uint32_t& bound) : out_(out), glsl_set_(glsl_set), bound_(bound) {}

    bool write(uint32_t type, uint32_t result, uint32_t x, float exponent) {
        if (exponent == 0.5f) {
            ext(type, result, GLSLstd450Sqrt, x);
        } else if (exponent == -0.5f) {
            ext(type, result, GLSLstd450InverseSqrt, x);
        } else if (exponent == 1.5f) {
            const uint32_t root = bound_++;
            ext(type, root, GLSLstd450Sqrt, x);
            mul(type, result, x, root);
        } else if (exponent == 2.0f) {
            mul(type, result, x, x);
        } else if (exponent == 2.5f) {
            const uint32_t square = bound_++, root = bound_++;
            mul(type, square, x, x);
            ext(type, root, GLSLstd450Sqrt, x);
            mul(type, result, square, root);
        } else if (exponent == 3.0f) {
            const uint32_t square = bound_++;
            mul(type, square, x, x);
            mul(type, result, square, x);
        } else if (exponent == 4.0f) {
            const uint32_t square = bound_++;
            mul(type, square, x, x);
            mul(type, result, square, square);
        } else {
            return false;
        }
        return true;
    }

private:
    void ext(uint32_t type, uint32_t result, uint32_t instruction, uint32_t x) {
        out_.insert(out_.end(), {(6u << 16) | spv::OpExtInst, type, result, glsl_set_, instruction, x});
    }
    void mul(uint32_t type, uint32_t result, uint32_t a, uint32_t b) {
        out_.insert(out_.end(), {(5u << 16) | spv::OpFMul, type, result, a, b});
    }

    SpirvBinary& out_;
    uint32_t glsl_set_;
    uint32_t& bound_;
};

}  // namespace

size_t reduce_constant_powers(SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords || words[0] != spv::MagicNumber) return 0;
    const auto parsed = detail::spirv_instructions(words);
    if (!parsed) return 0;
    const ConstantFacts facts = gather(words, *parsed);
    if (facts.glsl_set == 0) return 0;

    return detail::rewrite_instructions(words, *parsed, [&](const Instruction& in, SpirvBinary& out, uint32_t& bound) {
        const size_t a = in.offset;
        // OpExtInst type result set instruction x exponent
        if (in.opcode != spv::OpExtInst || in.count != 7 || words[a + 3] != facts.glsl_set || words[a + 4] != GLSLstd450Pow) return false;
        auto exponent = facts.values.find(words[a + 6]);
        PowWriter writer(out, facts.glsl_set, bound);
        return exponent != facts.values.end() && writer.write(words[a + 1], words[a + 2], words[a + 5], exponent->second);
    });
}

}  // namespace crtforge
