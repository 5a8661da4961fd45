// textureGather lowered to four reads, for GLSL before 4.00 / ES 3.10 and Godot's shading language.
//
// A RetroArch shader may gather one channel of a 2 x 2 footprint at once (lottesRVM's
// `textureGather(iChannel0, uv, 0)`); SPIRV-Cross refuses it for GLSL 3.30 and ES 3.00
// ("textureGather requires ESSL 310"). The footprint is the four texels linear filtering at uv
// would blend: with t = uv * size - 0.5, i0 = floor(t.x), j0 = floor(t.y), i1 = i0 + 1,
// j1 = j0 + 1, the result is (c(i0, j1), c(i1, j1), c(i1, j0), c(i0, j0)), component `comp` of
// each. Each texel is read at its centre, at level 0, through the same sampler, so the wrap mode
// (repeat, clamp, border) picks the same texel a gather would, and a linear sampler at a centre
// weighs that texel alone.
#include "targets/spirv_gather_lowering.hpp"

#include <spirv_cross/spirv.hpp>

#include <cstring>
#include <map>
#include <optional>
#include <vector>

#include "generator/spirv_words.hpp"
#include "targets/spirv_facts.hpp"

namespace crtforge::detail {
namespace {

constexpr uint32_t kGlslFloor = 8;  // GLSL.std.450 Floor

uint32_t word_of(float value) {
    uint32_t w = 0;
    std::memcpy(&w, &value, sizeof w);
    return w;
}

void emit(SpirvBinary& out, spv::Op op, std::initializer_list<uint32_t> operands) {
    out.push_back(static_cast<uint32_t>((operands.size() + 1) << 16) | static_cast<uint32_t>(op));
    out.insert(out.end(), operands.begin(), operands.end());
}

struct Module {
    uint32_t float_type = 0, vec2_type = 0, vec4_type = 0, int_type = 0, ivec2_type = 0, glsl = 0;
    bool image_query = false;
    std::map<uint32_t, uint32_t> sampled_image_of;  // OpTypeSampledImage -> its image type
    std::map<uint32_t, bool> image_2d_float;       // OpTypeImage -> a float, 2D, non-arrayed, single-sampled image
    std::map<uint32_t, uint32_t> constant_of;      // 32-bit integer constant -> its value
};

Module read_module(const SpirvBinary& w, const std::vector<SpirvInstruction>& list, const SpirvFacts& facts) {
    Module m;
    std::map<uint32_t, bool> float32;
    for (const SpirvInstruction& in : list) {
        auto at = [&](size_t i) { return w[in.offset + i]; };
        switch (in.opcode) {
            case spv::OpCapability:
                if (at(1) == spv::CapabilityImageQuery) m.image_query = true;
                break;
            case spv::OpExtInstImport:
                if (spirv_literal_string(w, in.offset + 2, in.offset + in.count) == "GLSL.std.450") m.glsl = at(1);
                break;
            case spv::OpTypeFloat:
                if (at(2) == 32) m.float_type = at(1), float32[at(1)] = true;
                break;
            case spv::OpTypeInt:
                if (at(2) == 32 && at(3) == 1) m.int_type = at(1);
                break;
            case spv::OpTypeImage:
                m.image_2d_float[at(1)] = float32.count(at(2)) && at(3) == spv::Dim2D && at(5) == 0 && at(6) == 0;
                break;
            case spv::OpTypeSampledImage: m.sampled_image_of[at(1)] = at(2); break;
            default: break;
        }
    }
    for (const auto& [id, vector] : facts.vectors) {
        if (vector.first == m.float_type && vector.second == 2) m.vec2_type = id;
        if (vector.first == m.float_type && vector.second == 4) m.vec4_type = id;
        if (m.int_type && vector.first == m.int_type && vector.second == 2) m.ivec2_type = id;
    }
    m.constant_of = facts.int_values;
    return m;
}

}  // namespace

size_t lower_texture_gathers(SpirvBinary& words) {
    auto list = spirv_instructions(words);
    if (!list) return 0;
    const SpirvFacts facts = gather_spirv_facts(words, *list);
    const Module m = read_module(words, *list, facts);
    // The gathers this can lower: a float vec4 from a float 2D texture, a constant component, no
    // image operands (offsets).
    auto lowerable = [&](const SpirvInstruction& in) {
        if (in.opcode != spv::OpImageGather || in.count != 6) return false;
        const uint32_t type = words[in.offset + 1], sampled = words[in.offset + 3], coord = words[in.offset + 4];
        const auto image = m.sampled_image_of.find(facts.type_of(sampled));
        const auto component = m.constant_of.find(words[in.offset + 5]);
        return type == m.vec4_type && m.vec4_type && m.vec2_type && m.glsl && facts.type_of(coord) == m.vec2_type &&
               image != m.sampled_image_of.end() && m.image_2d_float.count(image->second) && m.image_2d_float.at(image->second) &&
               component != m.constant_of.end() && component->second < 4;
    };
    size_t count = 0;
    for (const SpirvInstruction& in : *list) count += lowerable(in) ? 1 : 0;
    if (count == 0) return 0;

    uint32_t bound = words[3];
    // What the reads need, declared once before the first function: int and ivec2 where the
    // module has none, and the constants.
    const uint32_t int_type = m.int_type ? m.int_type : bound++;
    const uint32_t ivec2_type = m.ivec2_type ? m.ivec2_type : bound++;
    const uint32_t int_zero = bound++, float_zero = bound++, half = bound++, three_halves = bound++;
    const uint32_t centre[4] = {bound++, bound++, bound++, bound++};  // offsets of (i0,j1), (i1,j1), (i1,j0), (i0,j0)
    const float offset[4][2] = {{0.5f, 1.5f}, {1.5f, 1.5f}, {1.5f, 0.5f}, {0.5f, 0.5f}};

    SpirvBinary out(words.begin(), words.begin() + kSpirvHeaderWords);
    out.reserve(words.size() + count * 64 + 64);
    bool declared = false, capability = m.image_query;
    for (const SpirvInstruction& in : *list) {
        if (!capability && in.opcode != spv::OpCapability) {
            emit(out, spv::OpCapability, {spv::CapabilityImageQuery});  // textureSize's query
            capability = true;
        }
        if (!declared && in.opcode == spv::OpFunction) {
            if (!m.int_type) emit(out, spv::OpTypeInt, {int_type, 32, 1});
            if (!m.ivec2_type) emit(out, spv::OpTypeVector, {ivec2_type, int_type, 2});
            emit(out, spv::OpConstant, {int_type, int_zero, 0});
            emit(out, spv::OpConstant, {m.float_type, float_zero, word_of(0.0f)});
            emit(out, spv::OpConstant, {m.float_type, half, word_of(0.5f)});
            emit(out, spv::OpConstant, {m.float_type, three_halves, word_of(1.5f)});
            for (int c = 0; c < 4; ++c)
                emit(out, spv::OpConstantComposite,
                     {m.vec2_type, centre[c], offset[c][0] == 0.5f ? half : three_halves, offset[c][1] == 0.5f ? half : three_halves});
            declared = true;
        }
        if (!lowerable(in)) {
            out.insert(out.end(), words.begin() + static_cast<std::ptrdiff_t>(in.offset),
                       words.begin() + static_cast<std::ptrdiff_t>(in.offset + in.count));
            continue;
        }
        const uint32_t result = words[in.offset + 2], sampled = words[in.offset + 3], coord = words[in.offset + 4];
        const uint32_t component = m.constant_of.at(words[in.offset + 5]);
        const uint32_t image_type = m.sampled_image_of.at(facts.type_of(sampled));
        const uint32_t image = bound++, isize = bound++, size = bound++, scaled = bound++, shifted = bound++, corner = bound++;
        emit(out, spv::OpImage, {image_type, image, sampled});
        emit(out, spv::OpImageQuerySizeLod, {ivec2_type, isize, image, int_zero});
        emit(out, spv::OpConvertSToF, {m.vec2_type, size, isize});
        emit(out, spv::OpFMul, {m.vec2_type, scaled, coord, size});
        emit(out, spv::OpFSub, {m.vec2_type, shifted, scaled, centre[3]});  // uv * size - 0.5 (centre[3] is (0.5, 0.5))
        emit(out, spv::OpExtInst, {m.vec2_type, corner, m.glsl, kGlslFloor, shifted});  // (i0, j0)
        uint32_t texel[4];
        for (int c = 0; c < 4; ++c) {
            const uint32_t at = bound++, uv = bound++, read = bound++;
            texel[c] = bound++;
            emit(out, spv::OpFAdd, {m.vec2_type, at, corner, centre[c]});
            emit(out, spv::OpFDiv, {m.vec2_type, uv, at, size});
            emit(out, spv::OpImageSampleExplicitLod, {m.vec4_type, read, sampled, uv, spv::ImageOperandsLodMask, float_zero});
            emit(out, spv::OpCompositeExtract, {m.float_type, texel[c], read, component});
        }
        emit(out, spv::OpCompositeConstruct, {m.vec4_type, result, texel[0], texel[1], texel[2], texel[3]});
    }
    out[3] = bound;
    words = std::move(out);
    return count;
}

}  // namespace crtforge::detail
