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

#include <bit>
#include <map>
#include <optional>
#include <vector>

#include "generator/spirv_words.hpp"
#include "targets/spirv_facts.hpp"

namespace crtforge::detail {
namespace {

constexpr uint32_t kGlslFloor = 8;  // GLSL.std.450 Floor

struct Module {
    uint32_t float_type = 0, vec2_type = 0, vec4_type = 0, int_type = 0, ivec2_type = 0, glsl = 0;
    bool image_query = false;
    std::map<uint32_t, uint32_t> sampled_image_of;  // OpTypeSampledImage -> its image type
    std::map<uint32_t, bool> image_2d_float;       // OpTypeImage -> a float, 2D, non-arrayed, single-sampled image
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
        const auto component = facts.int_values.find(words[in.offset + 5]);
        return type == m.vec4_type && m.vec4_type && m.vec2_type && m.glsl && facts.type_of(coord) == m.vec2_type &&
               image != m.sampled_image_of.end() && m.image_2d_float.count(image->second) && m.image_2d_float.at(image->second) &&
               component != facts.int_values.end() && component->second < 4;
    };
    size_t count = 0;
    for (const SpirvInstruction& in : *list) count += lowerable(in) ? 1 : 0;
    if (count == 0) return 0;

    // What the reads need, declared once before the first function: int and ivec2 where the
    // module has none, and the constants.
    uint32_t next = words[3];
    const uint32_t int_type = m.int_type ? m.int_type : next++;
    const uint32_t ivec2_type = m.ivec2_type ? m.ivec2_type : next++;
    const uint32_t int_zero = next++, float_zero = next++, half = next++, three_halves = next++;
    const uint32_t centre[4] = {next++, next++, next++, next++};  // offsets of (i0,j1), (i1,j1), (i1,j0), (i0,j0)
    const bool offset_x_half[4] = {true, false, false, true}, offset_y_half[4] = {false, false, true, true};
    words[3] = next;

    bool declared = false, capability = m.image_query;
    rewrite_instructions(words, *list, [&](const SpirvInstruction& in, SpirvBinary& out, uint32_t& bound) {
        const bool first_function = !declared && in.opcode == spv::OpFunction;
        const bool first_past_capabilities = !capability && in.opcode != spv::OpCapability;
        if (!first_function && !first_past_capabilities && !lowerable(in)) return false;
        if (first_past_capabilities) {
            append_instruction(out, spv::OpCapability, {spv::CapabilityImageQuery});  // textureSize's query
            capability = true;
        }
        if (first_function) {
            if (!m.int_type) append_instruction(out, spv::OpTypeInt, {int_type, 32, 1});
            if (!m.ivec2_type) append_instruction(out, spv::OpTypeVector, {ivec2_type, int_type, 2});
            append_instruction(out, spv::OpConstant, {int_type, int_zero, 0});
            append_instruction(out, spv::OpConstant, {m.float_type, float_zero, std::bit_cast<uint32_t>(0.0f)});
            append_instruction(out, spv::OpConstant, {m.float_type, half, std::bit_cast<uint32_t>(0.5f)});
            append_instruction(out, spv::OpConstant, {m.float_type, three_halves, std::bit_cast<uint32_t>(1.5f)});
            for (int c = 0; c < 4; ++c)
                append_instruction(out, spv::OpConstantComposite, {m.vec2_type, centre[c], offset_x_half[c] ? half : three_halves,
                                                                   offset_y_half[c] ? half : three_halves});
            declared = true;
        }
        if (!lowerable(in)) {
            append_copy(out, words, in);
            return true;
        }
        const uint32_t result = words[in.offset + 2], sampled = words[in.offset + 3], coord = words[in.offset + 4];
        const uint32_t component = facts.int_values.at(words[in.offset + 5]);
        const uint32_t image_type = m.sampled_image_of.at(facts.type_of(sampled));
        const uint32_t image = bound++, isize = bound++, size = bound++, scaled = bound++, shifted = bound++, corner = bound++;
        append_instruction(out, spv::OpImage, {image_type, image, sampled});
        append_instruction(out, spv::OpImageQuerySizeLod, {ivec2_type, isize, image, int_zero});
        append_instruction(out, spv::OpConvertSToF, {m.vec2_type, size, isize});
        append_instruction(out, spv::OpFMul, {m.vec2_type, scaled, coord, size});
        append_instruction(out, spv::OpFSub, {m.vec2_type, shifted, scaled, centre[3]});  // uv * size - 0.5 (centre[3] is (0.5, 0.5))
        append_instruction(out, spv::OpExtInst, {m.vec2_type, corner, m.glsl, kGlslFloor, shifted});  // (i0, j0)
        uint32_t texel[4];
        for (int c = 0; c < 4; ++c) {
            const uint32_t at = bound++, uv = bound++, read = bound++;
            texel[c] = bound++;
            append_instruction(out, spv::OpFAdd, {m.vec2_type, at, corner, centre[c]});
            append_instruction(out, spv::OpFDiv, {m.vec2_type, uv, at, size});
            append_instruction(out, spv::OpImageSampleExplicitLod, {m.vec4_type, read, sampled, uv, spv::ImageOperandsLodMask, float_zero});
            append_instruction(out, spv::OpCompositeExtract, {m.float_type, texel[c], read, component});
        }
        append_instruction(out, spv::OpCompositeConstruct, {m.vec4_type, result, texel[0], texel[1], texel[2], texel[3]});
        return true;
    });
    return count;
}

}  // namespace crtforge::detail
