#include "runtime/vulkan/spirv_inspect.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

#include <fmt/core.h>

namespace crtforge::vulkan {
namespace {

constexpr uint32_t kMagic = 0x07230203;
constexpr size_t kHeaderWords = 5;

// Opcodes, decorations and storage classes used below (SPIR-V specification, section 3).
enum Op : uint32_t {
    OpName = 5, OpEntryPoint = 15, OpTypeBool = 20, OpTypeInt = 21, OpTypeFloat = 22, OpTypeVector = 23,
    OpTypeMatrix = 24, OpTypeImage = 25, OpTypeSampler = 26, OpTypeSampledImage = 27, OpTypeArray = 28,
    OpTypeRuntimeArray = 29, OpTypeStruct = 30, OpTypePointer = 32, OpConstant = 43, OpSpecConstant = 50,
    OpVariable = 59, OpDecorate = 71, OpMemberDecorate = 72,
};
enum Decoration : uint32_t {
    RowMajor = 4, Block = 2, BufferBlock = 3, ArrayStride = 6, MatrixStride = 7, BuiltIn = 11, Binding = 33,
    DescriptorSet = 34, Offset = 35,
};
enum StorageClass : uint32_t {
    UniformConstant = 0, Input = 1, Uniform = 2, PushConstant = 9, StorageBuffer = 12,
};
constexpr uint32_t kDimSubpassData = 6;

struct IdDecorations {
    std::optional<uint32_t> binding, set, array_stride;
    bool builtin = false, block = false, buffer_block = false;
};
struct MemberDecorations {
    std::optional<uint32_t> offset;
    uint32_t matrix_stride = 0;
    bool row_major = false;
};
struct Variable {
    uint32_t id = 0, pointer_type = 0, storage_class = 0;
};

// Everything read from the module, keyed by result id.
struct Module {
    std::vector<SpirvEntryPoint> entry_points;
    std::map<uint32_t, std::string> names;
    std::map<uint32_t, IdDecorations> decorations;
    std::map<std::pair<uint32_t, uint32_t>, MemberDecorations> members;
    std::map<uint32_t, std::vector<uint32_t>> types;  // id -> {opcode, operands after the result id...}
    std::map<uint32_t, uint32_t> constants;           // id -> low word of its value
    std::vector<Variable> variables;
};

// A nul-terminated literal string starting at words[0]; nullopt when it runs off the instruction.
std::optional<std::string> read_string(std::span<const uint32_t> words, size_t* consumed) {
    std::string out;
    for (size_t w = 0; w < words.size(); ++w) {
        for (int byte = 0; byte < 4; ++byte) {
            char c = static_cast<char>((words[w] >> (8 * byte)) & 0xffu);
            if (c == '\0') {
                if (consumed) *consumed = w + 1;
                return out;
            }
            out += c;
        }
    }
    return std::nullopt;
}

Result<Module> parse(std::span<const uint32_t> words, std::string_view what) {
    auto malformed = [&](std::string detail) {
        return make_error(fmt::format("{} is not valid SPIR-V: {}", what, detail));
    };
    if (words.empty()) return malformed("the module is empty");
    if (words.size() < kHeaderWords) return malformed(fmt::format("{} words is shorter than the header", words.size()));
    if (words[0] != kMagic) {
        return malformed(fmt::format("magic number is 0x{:08x}, expected 0x{:08x}", words[0], kMagic));
    }

    Module m;
    for (size_t at = kHeaderWords; at < words.size();) {
        const uint32_t count = words[at] >> 16, opcode = words[at] & 0xffffu;
        if (count == 0 || at + count > words.size()) {
            return malformed(fmt::format("instruction at word {} (opcode {}) has a bad word count {}", at, opcode, count));
        }
        std::span<const uint32_t> ops = words.subspan(at + 1, count - 1);  // operands
        auto need = [&](size_t n) { return ops.size() >= n; };
        switch (opcode) {
            case OpEntryPoint:
                if (need(3)) {
                    auto name = read_string(ops.subspan(2), nullptr);
                    if (!name) return malformed(fmt::format("unterminated entry point name at word {}", at));
                    m.entry_points.push_back({ops[0], *name});
                }
                break;
            case OpName:
                if (need(2)) {
                    if (auto name = read_string(ops.subspan(1), nullptr)) m.names[ops[0]] = *name;
                }
                break;
            case OpDecorate:
                if (need(2)) {
                    IdDecorations& d = m.decorations[ops[0]];
                    const bool arg = need(3);
                    switch (ops[1]) {
                        case Binding: if (arg) d.binding = ops[2]; break;
                        case DescriptorSet: if (arg) d.set = ops[2]; break;
                        case ArrayStride: if (arg) d.array_stride = ops[2]; break;
                        case BuiltIn: d.builtin = true; break;
                        case Block: d.block = true; break;
                        case BufferBlock: d.buffer_block = true; break;
                        default: break;
                    }
                }
                break;
            case OpMemberDecorate:
                if (need(3)) {
                    MemberDecorations& d = m.members[{ops[0], ops[1]}];
                    const bool arg = need(4);
                    if (ops[2] == Offset && arg) d.offset = ops[3];
                    if (ops[2] == MatrixStride && arg) d.matrix_stride = ops[3];
                    if (ops[2] == RowMajor) d.row_major = true;
                }
                break;
            case OpTypeBool: case OpTypeInt: case OpTypeFloat: case OpTypeVector: case OpTypeMatrix:
            case OpTypeImage: case OpTypeSampler: case OpTypeSampledImage: case OpTypeArray:
            case OpTypeRuntimeArray: case OpTypeStruct: case OpTypePointer:
                if (need(1)) {
                    std::vector<uint32_t> type{opcode};
                    type.insert(type.end(), ops.begin() + 1, ops.end());
                    m.types[ops[0]] = std::move(type);
                }
                break;
            case OpConstant: case OpSpecConstant:
                if (need(3)) m.constants[ops[1]] = ops[2];
                break;
            case OpVariable:
                if (need(3)) m.variables.push_back({ops[1], ops[0], ops[2]});
                break;
            default: break;
        }
        at += count;
    }
    return m;
}

// Type lookups, tolerant of ids that were never defined (the answer is then "unknown").
const std::vector<uint32_t>* type_of(const Module& m, uint32_t id) {
    auto it = m.types.find(id);
    return it == m.types.end() ? nullptr : &it->second;
}

// Bytes a value of `type` covers from its offset to its last byte, as laid out in a block.
// `member` carries the matrix layout, which SPIR-V decorates on the enclosing struct member.
std::optional<uint64_t> extent_of(const Module& m, uint32_t type_id, const MemberDecorations& member, int depth = 0) {
    const auto* t = type_of(m, type_id);
    if (!t || depth > 32) return std::nullopt;  // depth: malformed modules could nest types in a cycle
    const auto operand = [&](size_t i) -> std::optional<uint32_t> {
        return i < t->size() ? std::optional<uint32_t>((*t)[i]) : std::nullopt;
    };
    switch ((*t)[0]) {
        case OpTypeInt:
        case OpTypeFloat: {
            auto width = operand(1);
            return width ? std::optional<uint64_t>(*width / 8) : std::nullopt;
        }
        case OpTypeVector: {
            auto component = operand(1), count = operand(2);
            if (!component || !count) return std::nullopt;
            auto size = extent_of(m, *component, member, depth + 1);
            return size ? std::optional<uint64_t>(*size * *count) : std::nullopt;
        }
        case OpTypeMatrix: {
            auto column = operand(1), columns = operand(2);
            const auto* column_type = column ? type_of(m, *column) : nullptr;
            if (!columns || !column_type || column_type->size() < 3) return std::nullopt;
            auto scalar = extent_of(m, (*column_type)[1], member, depth + 1);
            if (!scalar) return std::nullopt;
            const uint64_t rows = (*column_type)[2];
            // Column-major: `columns` vectors of `rows` scalars, `matrix_stride` apart; row-major swaps.
            const uint64_t vectors = member.row_major ? rows : *columns;
            const uint64_t length = member.row_major ? *columns : rows;
            if (member.matrix_stride == 0) return vectors * length * *scalar;
            return (vectors - 1) * member.matrix_stride + length * *scalar;
        }
        case OpTypeArray: {
            auto element = operand(1), length_id = operand(2);
            if (!element || !length_id) return std::nullopt;
            auto length = m.constants.find(*length_id);
            auto size = extent_of(m, *element, member, depth + 1);
            if (length == m.constants.end() || !size || length->second == 0) return std::nullopt;
            auto stride = m.decorations.count(type_id) ? m.decorations.at(type_id).array_stride : std::nullopt;
            if (!stride) return *size * length->second;
            return (length->second - 1) * uint64_t{*stride} + *size;
        }
        case OpTypeRuntimeArray: return uint64_t{0};
        case OpTypeStruct: {
            uint64_t end = 0;
            for (uint32_t i = 1; i < t->size(); ++i) {
                auto it = m.members.find({type_id, i - 1});
                const MemberDecorations layout = it == m.members.end() ? MemberDecorations{} : it->second;
                if (!layout.offset) return std::nullopt;
                auto size = extent_of(m, (*t)[i], layout, depth + 1);
                if (!size) return std::nullopt;
                end = std::max(end, *layout.offset + *size);
            }
            return end;
        }
        default: return std::nullopt;
    }
}

// Classifies one descriptor-backed variable; nullopt for variables that are not descriptors.
std::optional<SpirvResource> classify(const Module& m, const Variable& v) {
    if (v.storage_class != UniformConstant && v.storage_class != Uniform && v.storage_class != StorageBuffer) {
        return std::nullopt;
    }
    const auto* pointer = type_of(m, v.pointer_type);
    if (!pointer || (*pointer)[0] != OpTypePointer || pointer->size() < 3) return std::nullopt;

    SpirvResource r;
    uint32_t base = (*pointer)[2];
    if (const auto* t = type_of(m, base); t && ((*t)[0] == OpTypeArray || (*t)[0] == OpTypeRuntimeArray)) {
        r.array_size = 0;  // runtime array: unbounded
        if ((*t)[0] == OpTypeArray && t->size() > 2) {
            auto length = m.constants.find((*t)[2]);
            r.array_size = length == m.constants.end() ? 0 : length->second;
        }
        base = t->size() > 1 ? (*t)[1] : 0;
    }
    const auto* t = type_of(m, base);
    const IdDecorations none;
    const IdDecorations& var_dec = m.decorations.count(v.id) ? m.decorations.at(v.id) : none;
    const IdDecorations& base_dec = m.decorations.count(base) ? m.decorations.at(base) : none;
    r.set = var_dec.set.value_or(0);
    r.binding = var_dec.binding.value_or(0);
    if (m.names.count(v.id) && !m.names.at(v.id).empty()) {
        r.name = m.names.at(v.id);
    } else if (m.names.count(base)) {
        r.name = m.names.at(base);
    }

    const uint32_t opcode = t ? (*t)[0] : 0;
    if (v.storage_class == StorageBuffer || (opcode == OpTypeStruct && base_dec.buffer_block)) {
        r.kind = SpirvResourceKind::StorageBuffer;
    } else if (v.storage_class == Uniform && opcode == OpTypeStruct) {
        r.kind = SpirvResourceKind::UniformBuffer;
        r.block_bytes = extent_of(m, base, MemberDecorations{}).value_or(0);
    } else if (opcode == OpTypeSampledImage) {
        r.kind = SpirvResourceKind::CombinedImageSampler;
    } else if (opcode == OpTypeSampler) {
        r.kind = SpirvResourceKind::Sampler;
    } else if (opcode == OpTypeImage && t->size() > 6) {
        // OpTypeImage operands: sampled type, Dim, depth, arrayed, MS, Sampled (1 = sampled, 2 = storage).
        if ((*t)[2] == kDimSubpassData) r.kind = SpirvResourceKind::Other;
        else r.kind = (*t)[6] == 2 ? SpirvResourceKind::StorageImage : SpirvResourceKind::SampledImage;
    }
    return r;
}

bool is_builtin_input(const Module& m, const Variable& v) {
    if (m.decorations.count(v.id) && m.decorations.at(v.id).builtin) return true;
    // Built-in blocks (gl_PerVertex) carry BuiltIn on their members instead.
    const auto* pointer = type_of(m, v.pointer_type);
    if (!pointer || pointer->size() < 3) return false;
    // Only built-in blocks have member decorations on inputs (vertex inputs cannot be user blocks).
    const uint32_t pointee = (*pointer)[2];
    auto it = m.members.lower_bound({pointee, 0});
    return it != m.members.end() && it->first.first == pointee;
}

}  // namespace

const char* resource_kind_name(SpirvResourceKind kind) {
    switch (kind) {
        case SpirvResourceKind::UniformBuffer: return "uniform buffer";
        case SpirvResourceKind::CombinedImageSampler: return "combined image sampler";
        case SpirvResourceKind::SampledImage: return "sampled image";
        case SpirvResourceKind::Sampler: return "sampler";
        case SpirvResourceKind::StorageBuffer: return "storage buffer";
        case SpirvResourceKind::StorageImage: return "storage image";
        case SpirvResourceKind::Other: break;
    }
    return "descriptor";
}

Result<SpirvInterface> inspect_spirv(std::span<const uint32_t> words, std::string_view what) {
    auto parsed = parse(words, what);
    if (!parsed) return parsed.error();
    const Module& m = parsed.value();

    SpirvInterface out;
    out.entry_points = m.entry_points;
    for (const Variable& v : m.variables) {
        if (auto resource = classify(m, v)) out.resources.push_back(std::move(*resource));
        if (v.storage_class == PushConstant) out.push_constants = true;
        if (v.storage_class == Input && !is_builtin_input(m, v)) out.user_inputs = true;
    }
    return out;
}

bool has_entry_point(const SpirvInterface& module, ExecutionModel model, std::string_view name) {
    return std::any_of(module.entry_points.begin(), module.entry_points.end(), [&](const SpirvEntryPoint& e) {
        return e.execution_model == static_cast<uint32_t>(model) && e.name == name;
    });
}

}  // namespace crtforge::vulkan
