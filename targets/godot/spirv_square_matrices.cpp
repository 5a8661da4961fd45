// Non-square matrices as square ones, for Godot, whose shading language has mat2, mat3 and mat4 only.
//
// RetroArch's shaders use mat4x3 (four colours as columns: `mat4x3(a, b, c, d) * weights` blends
// them, `luma * mat4x3(...)` takes four lumas at once) and mat3x2, in 33 presets under crt/. A
// matCxR padded to matN (N = max(C, R)) with zero rows and columns computes the same values: the
// product with a vector padded by zeros has the old result in its first components and zeros after
// (no rounding: every extra term is an exact 0 * x added to a sum). So the padding is done once, on
// the module: the matrix type is redeclared square, and each instruction that hands a column or a
// vector across the matrix boundary pads what goes in (OpCompositeConstruct with 0.0) and shrinks
// what comes out (OpVectorShuffle), keeping every other value's type. SPIRV-Cross then prints
// `mat4(vec4(a, 0.0), ...)` and `(m * w).xyz`, which Godot compiles.
//
// Matrix types are not aggregates: SPIR-V forbids two declarations of the same matrix type, so
// every matrix type that ends up matN (an existing mat4 and a padded mat4x3, say) is merged into
// whichever of them the module declares first.
#include "targets/godot/spirv_square_matrices.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <spirv_cross/spirv.hpp>
#include <spirv_cross/spirv_cross_error_handling.hpp>

#include "generator/spirv_words.hpp"
#include "targets/spirv_facts.hpp"

namespace crtforge::godot {
namespace {

using detail::append_instruction;

[[noreturn]] void refuse(const std::string& what) {
    throw spirv_cross::CompilerError("Godot has no non-square matrix type, and crtforge cannot pad " + what);
}

// A non-square matrix type and what it becomes.
struct Padding {
    uint32_t columns = 0, rows = 0, n = 0;
    uint32_t column = 0;  // its column type, vecR
};

// What the rewrite needs to know of the module as it was, and the matrix types it pads.
struct ModuleFacts : detail::SpirvFacts {
    std::map<uint32_t, Padding> padded;  // non-square matrix type -> padding
};

ModuleFacts gather(const SpirvBinary& w, const std::vector<detail::SpirvInstruction>& list) {
    ModuleFacts f;
    static_cast<detail::SpirvFacts&>(f) = detail::gather_spirv_facts(w, list);
    for (const auto& [id, matrix] : f.matrices) {
        auto column = f.vectors.find(matrix.first);
        if (column == f.vectors.end()) continue;
        const uint32_t rows = column->second.second, columns = matrix.second;
        if (rows != columns) f.padded[id] = {columns, rows, std::max(rows, columns), matrix.first};
    }
    return f;
}

// Whether `type` holds a padded matrix (through arrays and structs).
bool holds_padded(const ModuleFacts& f, uint32_t type, int depth = 0) {
    if (depth > 64) return false;
    if (f.padded.count(type)) return true;
    if (uint32_t e = f.element(type)) return holds_padded(f, e, depth + 1);
    if (auto s = f.structs.find(type); s != f.structs.end())
        return std::any_of(s->second.begin(), s->second.end(), [&](uint32_t m) { return holds_padded(f, m, depth + 1); });
    return false;
}

// The rewrite: the facts, the ids it allocates, the square matrix type each matrix type becomes.
class Squarer {
public:
    Squarer(const SpirvBinary& w, const std::vector<detail::SpirvInstruction>& list) : w_(w), f_(gather(w, list)) {}

    size_t padded_count() const { return f_.padded.size(); }

    void plan(uint32_t& bound) {
        for (const auto& [s, members] : f_.structs)
            if (f_.blocks.count(s) && holds_padded(f_, s)) refuse("a uniform or storage block member (the host fixes its layout)");
        for (const auto& [id, p] : f_.padded) {
            const auto& column = f_.vectors.at(p.column);
            if (float_ == 0) float_ = column.first;
            if (column.first != float_) refuse("matrices of two component types");
        }
        // Each N in use: its vector type (found or made), and the matrix type every matN merges into.
        for (const auto& [id, p] : f_.padded) sizes_.insert(p.n);
        for (uint32_t n : sizes_) {
            for (const auto& [id, v] : f_.vectors)
                if (v.first == float_ && v.second == n && wide_.count(n) == 0) wide_[n] = id;
            std::vector<uint32_t> group;
            for (const auto& [id, m] : f_.matrices) {
                auto column = f_.vectors.find(m.first);
                if (column == f_.vectors.end() || column->second.first != float_) continue;
                if ((f_.padded.count(id) && f_.padded.at(id).n == n) || (column->second.second == n && m.second == n)) group.push_back(id);
            }
            std::sort(group.begin(), group.end(), [&](uint32_t x, uint32_t y) { return f_.declared_at.at(x) < f_.declared_at.at(y); });
            for (uint32_t id : group) merged_[id] = group.front();
            insert_at_ = std::min(insert_at_, f_.declared_at.at(group.front()));
        }
        // New declarations go before the first merged matrix type: a zero, each vecN (moved there when
        // the module declares it later), its zero vector, and pointers to it for column access chains.
        zero_ = bound++;
        append_instruction(declarations_, spv::OpConstantNull, {float_, zero_});
        for (uint32_t n : sizes_) {
            auto found = wide_.find(n);
            if (found == wide_.end()) {
                wide_[n] = bound++;
                append_instruction(declarations_, spv::OpTypeVector, {wide_[n], float_, n});
            } else if (f_.declared_at.at(found->second) > insert_at_) {
                moved_.insert(found->second);
                append_instruction(declarations_, spv::OpTypeVector, {found->second, float_, n});
            }
            zero_vector_[n] = bound++;
            append_instruction(declarations_, spv::OpConstantNull, {wide_[n], zero_vector_[n]});
        }
        for (const auto& [id, pointer] : f_.pointers) {
            if (!holds_padded(f_, pointer.second) && !f_.padded.count(pointer.second)) continue;
            for (const auto& [pid, p] : f_.padded) {
                const auto key = std::make_pair(pointer.first, p.n);
                if (column_pointer_.count(key)) continue;
                column_pointer_[key] = bound++;
                append_instruction(declarations_, spv::OpTypePointer, {column_pointer_[key], pointer.first, wide_.at(p.n)});
            }
        }
    }

    // Appends what replaces instruction `in` to `out`; false keeps it as it is.
    bool rewrite(const detail::SpirvInstruction& in, SpirvBinary& out, uint32_t& bound) {
        std::vector<uint32_t> inst(w_.begin() + static_cast<long>(in.offset), w_.begin() + static_cast<long>(in.offset + in.count));
        const auto op = static_cast<spv::Op>(in.opcode);
        if (in.offset == insert_at_) out.insert(out.end(), declarations_.begin(), declarations_.end());
        if (op == spv::OpTypeVector && moved_.count(inst[1])) return true;
        if (op == spv::OpTypeMatrix) {
            auto m = merged_.find(inst[1]);
            if (m == merged_.end()) return false;
            if (m->second != inst[1]) return true;  // merged into the first matN
            auto p = f_.padded.find(inst[1]);
            if (p == f_.padded.end()) return in.offset == insert_at_ ? keep(out, inst) : false;
            append_instruction(out, spv::OpTypeMatrix, {inst[1], wide_.at(p->second.n), p->second.n});
            return true;
        }
        if ((op == spv::OpName || op == spv::OpDecorate) && inst.size() >= 2 && merged_.count(inst[1]) && merged_.at(inst[1]) != inst[1])
            return true;  // names and decorations of a merged-away matrix type
        remap_types(op, inst);
        switch (op) {
            case spv::OpConstantComposite:
            case spv::OpCompositeConstruct:
                if (auto p = padding_of_type(original_type(inst))) {
                    std::vector<uint32_t> columns;
                    for (size_t i = 3; i < inst.size(); ++i)
                        columns.push_back(op == spv::OpConstantComposite ? padded_constant(out, bound, inst[i], *p)
                                                                         : pad(out, bound, inst[i], p->rows, p->n));
                    while (columns.size() < p->n) columns.push_back(zero_vector_.at(p->n));
                    inst.resize(3);
                    inst.insert(inst.end(), columns.begin(), columns.end());
                }
                return keep(out, inst);
            case spv::OpSpecConstantComposite:
            case spv::OpSpecConstantOp:
                if (padding_of_type(original_type(inst))) refuse("a specialisation constant matrix");
                return keep(out, inst);
            case spv::OpMatrixTimesVector:  // vecR = matCxR * vecC
                if (auto p = padding_of_value(inst[3])) {
                    inst[4] = pad(out, bound, inst[4], p->columns, p->n);
                    return widen_result(out, bound, inst, p->rows, p->n);
                }
                return keep(out, inst);
            case spv::OpVectorTimesMatrix:  // vecC = vecR * matCxR
                if (auto p = padding_of_value(inst[4])) {
                    inst[3] = pad(out, bound, inst[3], p->rows, p->n);
                    return widen_result(out, bound, inst, p->columns, p->n);
                }
                return keep(out, inst);
            case spv::OpOuterProduct:  // matCxR = vecR outer vecC
                if (auto p = padding_of_type(original_type(inst))) {
                    inst[3] = pad(out, bound, inst[3], p->rows, p->n);
                    inst[4] = pad(out, bound, inst[4], p->columns, p->n);
                }
                return keep(out, inst);
            case spv::OpMatrixTimesMatrix:
            case spv::OpTranspose: {
                std::vector<uint32_t> sizes{square_size(original_type(inst))};
                for (size_t i = 3; i < inst.size(); ++i) sizes.push_back(square_size(value_type(inst[i])));
                const bool any_padded = padding_of_type(original_type(inst)) || padding_of_value(inst[3]) ||
                                        (inst.size() > 4 && padding_of_value(inst[4]));
                if (any_padded && std::adjacent_find(sizes.begin(), sizes.end(), std::not_equal_to<>()) != sizes.end())
                    refuse("a product or transpose mixing it with a matrix of another size");
                return keep(out, inst);
            }
            case spv::OpCompositeExtract:  // type result composite indices...
                if (auto p = column_reached(value_type(inst[3]), inst, 4, false))
                    return widen_result(out, bound, inst, p->rows, p->n);
                return keep(out, inst);
            case spv::OpCompositeInsert:  // type result object composite indices...
                if (auto p = column_reached(original_type(inst), inst, 5, false)) inst[3] = pad(out, bound, inst[3], p->rows, p->n);
                return keep(out, inst);
            case spv::OpAccessChain:
            case spv::OpInBoundsAccessChain: {
                auto base = f_.value_types.find(inst[3]);
                auto pointer = base == f_.value_types.end() ? f_.pointers.end() : f_.pointers.find(base->second);
                if (pointer == f_.pointers.end()) return keep(out, inst);
                if (auto p = column_reached(pointer->second.second, inst, 4, true)) {
                    inst[1] = column_pointer_.at({pointer->second.first, p->n});
                    column_pointers_[inst[2]] = *p;
                }
                return keep(out, inst);
            }
            case spv::OpLoad:
                if (auto c = column_pointers_.find(inst[3]); c != column_pointers_.end())
                    return widen_result(out, bound, inst, c->second.rows, c->second.n);
                return keep(out, inst);
            case spv::OpStore:
                if (auto c = column_pointers_.find(inst[1]); c != column_pointers_.end())
                    inst[2] = pad(out, bound, inst[2], c->second.rows, c->second.n);
                return keep(out, inst);
            default:
                if (detail::hands_pointers_on(op))
                    for (size_t i = 1; i < inst.size(); ++i)
                        if (column_pointers_.count(inst[i])) refuse("a pointer to one of its columns passed on");
                return keep(out, inst);
        }
    }

private:
    static bool keep(SpirvBinary& out, std::vector<uint32_t>& inst) {
        inst[0] = (static_cast<uint32_t>(inst.size()) << 16) | (inst[0] & 0xffffu);
        out.insert(out.end(), inst.begin(), inst.end());
        return true;
    }

    uint32_t value_type(uint32_t value) const { return f_.type_of(value); }
    uint32_t original_type(const std::vector<uint32_t>& inst) const { return value_type(inst.size() > 2 ? inst[2] : 0); }
    const Padding* padding_of_type(uint32_t type) const {
        auto p = f_.padded.find(type);
        return p == f_.padded.end() ? nullptr : &p->second;
    }
    const Padding* padding_of_value(uint32_t value) const { return padding_of_type(value_type(value)); }
    // The side of the square a matrix type ends as (0: not a float matrix).
    uint32_t square_size(uint32_t type) const {
        if (auto p = padding_of_type(type)) return p->n;
        auto m = f_.matrices.find(type);
        return m == f_.matrices.end() ? 0 : m->second.second;
    }

    // Every type operand naming a matrix type merged into another names that one.
    void remap_types(spv::Op op, std::vector<uint32_t>& inst) const {
        auto remap = [&](uint32_t& id) {
            auto m = merged_.find(id);
            if (m != merged_.end()) id = m->second;
        };
        bool has_result = false, has_type = false;
        spv::HasResultAndType(op, &has_result, &has_type);
        if (has_type && inst.size() > 1) remap(inst[1]);
        if (op == spv::OpTypePointer && inst.size() > 3) remap(inst[3]);
        if ((op == spv::OpTypeArray || op == spv::OpTypeRuntimeArray) && inst.size() > 2) remap(inst[2]);
        if (op == spv::OpTypeStruct || op == spv::OpTypeFunction)
            for (size_t i = 2; i < inst.size(); ++i) remap(inst[i]);
    }

    // Follows `type` through the indices inst[first...] (ids for an access chain, literals for a
    // composite); the padding when the last index picks a column of a padded matrix.
    const Padding* column_reached(uint32_t type, const std::vector<uint32_t>& inst, size_t first, bool ids) const {
        for (size_t i = first; i < inst.size(); ++i) {
            if (auto p = padding_of_type(type)) {
                if (i + 1 == inst.size()) return p;
                type = p->column;
            } else if (uint32_t e = f_.element(type)) {
                type = e;
            } else if (auto m = f_.matrices.find(type); m != f_.matrices.end()) {
                type = m->second.first;
            } else if (auto s = f_.structs.find(type); s != f_.structs.end()) {
                uint32_t index = inst[i];
                if (ids) {
                    auto c = f_.int_values.find(inst[i]);
                    if (c == f_.int_values.end()) return nullptr;
                    index = c->second;
                }
                if (index >= s->second.size()) return nullptr;
                type = s->second[index];
            } else {
                return nullptr;
            }
        }
        return nullptr;
    }

    // A float vector of `from` components as one of `n`, zeros after.
    uint32_t pad(SpirvBinary& out, uint32_t& bound, uint32_t value, uint32_t from, uint32_t n) {
        if (from >= n) return value;
        const uint32_t id = bound++;
        out.push_back(((3 + 1 + n - from) << 16) | spv::OpCompositeConstruct);
        out.insert(out.end(), {wide_.at(n), id, value});
        for (uint32_t i = from; i < n; ++i) out.push_back(zero_);
        return id;
    }
    // A constant column of a padded matrix, as a constant vecN.
    uint32_t padded_constant(SpirvBinary& out, uint32_t& bound, uint32_t column, const Padding& p) {
        if (f_.constant_nulls.count(column)) return zero_vector_.at(p.n);
        auto parts = f_.constant_composites.find(column);
        if (parts == f_.constant_composites.end()) refuse("a constant column it cannot read");
        const uint32_t id = bound++;
        out.push_back(((3 + p.n) << 16) | spv::OpConstantComposite);
        out.insert(out.end(), {wide_.at(p.n), id});
        out.insert(out.end(), parts->second.begin(), parts->second.end());
        for (uint32_t i = p.rows; i < p.n; ++i) out.push_back(zero_);
        return id;
    }
    // `inst` (type result ...) computed as vecN and shrunk to its `count` components.
    bool widen_result(SpirvBinary& out, uint32_t& bound, std::vector<uint32_t>& inst, uint32_t count, uint32_t n) {
        if (count >= n) return keep(out, inst);
        const uint32_t type = inst[1], result = inst[2], wide = bound++;
        inst[1] = wide_.at(n);
        inst[2] = wide;
        keep(out, inst);
        out.push_back(((5 + count) << 16) | spv::OpVectorShuffle);
        out.insert(out.end(), {type, result, wide, wide});
        for (uint32_t i = 0; i < count; ++i) out.push_back(i);
        return true;
    }

    const SpirvBinary& w_;
    ModuleFacts f_;
    uint32_t float_ = 0, zero_ = 0;
    size_t insert_at_ = SIZE_MAX;
    std::set<uint32_t> sizes_, moved_;
    std::map<uint32_t, uint32_t> wide_, zero_vector_, merged_;  // by N: vecN, its zero; matrix type -> the matN it merges into
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> column_pointer_;  // {storage class, N} -> pointer to vecN
    std::map<uint32_t, Padding> column_pointers_;                       // access chain result -> its matrix
    SpirvBinary declarations_;
};

}  // namespace

size_t square_matrices(SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords || words[0] != spv::MagicNumber) return 0;
    const auto parsed = detail::spirv_instructions(words);
    if (!parsed) return 0;
    Squarer squarer(words, *parsed);
    const size_t count = squarer.padded_count();
    if (count == 0) return 0;
    squarer.plan(words[3]);  // the ids it declares up front
    detail::rewrite_instructions(words, *parsed, [&](const detail::SpirvInstruction& in, SpirvBinary& out, uint32_t& bound) {
        return squarer.rewrite(in, out, bound);
    });
    return count;
}

}  // namespace crtforge::godot
