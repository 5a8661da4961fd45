// Arrays of arrays flattened, for GLSL before 4.30 / ES 3.10 and Godot's shading language.
//
// RetroArch's shaders keep tables as arrays of arrays (crt-geom's and crt-hyllian's mask tables,
// `const vec3 masks[4][2]`, vt220's glyph rows): SPIRV-Cross refuses them for GLSL 3.30 and ES 3.00
// ("Arrays of arrays not supported"), and Godot has none. Row-major, T a[n][m] is T a[n * m] with
// a[i][j] at i * m + j, so the module is rewritten once, before SPIRV-Cross sees it:
// - each array of arrays is redeclared as one array of its leaf type, its constants listed leaf by leaf;
// - an index path through it (access chain, extract, insert) takes one flat index instead of one
//   per level: a constant where all its indices are, else i * m + j computed in the function;
// - a path that stops at a row (`vec3 row[2] = masks[i]`) reads or writes the row's leaves one by
//   one: a pointer to a row is never emitted, its loads and stores become per-leaf ones.
#include "targets/spirv_flat_arrays.hpp"

#include <spirv_cross/spirv.hpp>
#include <spirv_cross/spirv_cross_error_handling.hpp>

#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "generator/spirv_debug_names.hpp"
#include "generator/spirv_words.hpp"
#include "targets/spirv_facts.hpp"

namespace crtforge::detail {
namespace {

[[noreturn]] void refuse(const std::string& what) {
    throw spirv_cross::CompilerError("arrays of arrays are flattened for this target, but not " + what);
}

// An array of arrays as its flat form: the levels' lengths, outermost first, and the leaf type.
struct Flat {
    std::vector<uint32_t> dims;
    uint32_t leaf = 0, length_type = 0;
    uint32_t total(size_t from = 0) const {
        return std::accumulate(dims.begin() + static_cast<long>(from), dims.end(), 1u, std::multiplies<>());
    }
};

// An index: a value id, or a number known now (a literal, or the value of a constant id).
struct Index {
    uint32_t id = 0;
    std::optional<uint32_t> value;
    uint32_t type = 0;  // its integer type (paths of ids)
};

class Flattener {
public:
    Flattener(const SpirvBinary& w, const std::vector<SpirvInstruction>& list) : w_(w), list_(list) { gather(); }

    size_t flat_count() const { return flat_.size(); }

    SpirvBinary run() {
        for (const auto& [s, members] : f_.structs)
            if (f_.blocks.count(s) && holds_flat(s, 0)) refuse("in a uniform or storage block (the host fixes its layout)");
        SpirvBinary out(w_.begin(), w_.begin() + kSpirvHeaderWords);
        size_t late_at = 0;
        for (const SpirvInstruction& in : list_) {
            if (in.opcode == spv::OpFunction && !in_functions_) {
                in_functions_ = true;
                late_at = out.size();
            }
            std::vector<uint32_t> inst(w_.begin() + static_cast<long>(in.offset), w_.begin() + static_cast<long>(in.offset + in.count));
            rewrite(static_cast<spv::Op>(in.opcode), inst, out);
        }
        // Declarations first needed inside a function go at the end of the global section.
        out.insert(out.begin() + static_cast<long>(in_functions_ ? late_at : out.size()), late_.begin(), late_.end());
        out[3] = bound_;
        return out;
    }

private:
    void gather() {
        bound_ = w_[3];
        f_ = gather_spirv_facts(w_, list_);
        for (const auto& [id, array] : f_.arrays) {
            if (!element(array.first)) continue;
            Flat f;
            for (uint32_t t = id; element(t); t = element(t)) {
                auto length = f_.int_values.find(f_.arrays.count(t) ? f_.arrays.at(t).second : 0);
                if (length == f_.int_values.end()) refuse("an array of arrays sized at run time or by a specialisation constant");
                f.dims.push_back(length->second);
                f.length_type = f_.type_of(length->first);
                f.leaf = element(t);
            }
            flat_[id] = f;
        }
        for (const auto& [id, element] : f_.runtime_arrays)
            if (f_.arrays.count(element)) refuse("a runtime-sized array of arrays");
    }

    uint32_t element(uint32_t array) const { return f_.element(array); }
    bool holds_flat(uint32_t type, int depth) const {
        if (depth > 64) return false;
        if (flat_.count(type)) return true;
        if (uint32_t e = element(type)) return holds_flat(e, depth + 1);
        if (auto s = f_.structs.find(type); s != f_.structs.end())
            for (uint32_t m : s->second)
                if (holds_flat(m, depth + 1)) return true;
        return false;
    }
    uint32_t type_of(uint32_t value) const { return f_.type_of(value); }
    // How many leaves a value of `type` holds once flat (1 for a non-array).
    uint32_t leaves(uint32_t type) const {
        if (auto f = flat_.find(type); f != flat_.end()) return f->second.total();
        if (auto a = f_.arrays.find(type); a != f_.arrays.end()) return f_.int_values.count(a->second.second) ? f_.int_values.at(a->second.second) : 1;
        return 1;
    }
    uint32_t leaf_of(uint32_t type) const {
        if (auto f = flat_.find(type); f != flat_.end()) return f->second.leaf;
        return element(type);
    }

    // New ids and declarations. Inside a function, declarations wait in late_; in the global section
    // they go straight out, before the instruction that needs them.
    SpirvBinary& declarations(SpirvBinary& out) { return in_functions_ ? late_ : out; }
    uint32_t constant(SpirvBinary& out, uint32_t type, uint32_t value) {
        auto found = constants_.find({type, value});
        if (found != constants_.end()) return found->second;
        const uint32_t id = bound_++;
        declarations(out).insert(declarations(out).end(), {(4u << 16) | spv::OpConstant, type, id, value});
        constants_[{type, value}] = id;
        f_.int_values[id] = value;
        f_.value_types[id] = type;
        return id;
    }
    uint32_t null_of(SpirvBinary& out, uint32_t type) {
        auto found = null_of_.find(type);
        if (found != null_of_.end()) return found->second;
        const uint32_t id = bound_++;
        declarations(out).insert(declarations(out).end(), {(3u << 16) | spv::OpConstantNull, type, id});
        return null_of_[type] = id;
    }
    uint32_t pointer_to(SpirvBinary& out, uint32_t storage, uint32_t type) {
        for (const auto& [id, p] : f_.pointers)
            if (p.first == storage && p.second == type) return id;
        const uint32_t id = bound_++;
        declarations(out).insert(declarations(out).end(), {(4u << 16) | spv::OpTypePointer, id, storage, type});
        f_.pointers[id] = {storage, type};
        return id;
    }

    // The leaves of a constant of `type`, in flat order (null constants as null leaves).
    void constant_leaves(SpirvBinary& out, uint32_t c, uint32_t type, std::vector<uint32_t>& into) {
        const uint32_t e = element(type);
        if (e == 0) return into.push_back(c);
        if (f_.constant_nulls.count(c)) {
            const uint32_t n = leaves(type), leaf_null = null_of(out, leaf_of(type));
            into.insert(into.end(), n, leaf_null);
            return;
        }
        auto parts = f_.constant_composites.find(c);
        if (parts == f_.constant_composites.end()) refuse("a constant row it cannot read");
        for (uint32_t part : parts->second) constant_leaves(out, part, e, into);
    }
    // The leaves of a value of array type `type` (already flat in form), extracted one by one.
    std::vector<uint32_t> value_leaves(SpirvBinary& out, uint32_t value, uint32_t type) {
        std::vector<uint32_t> ids;
        for (uint32_t t = 0; t < leaves(type); ++t) {
            ids.push_back(bound_++);
            append_instruction(out, spv::OpCompositeExtract, {leaf_of(type), ids.back(), value, t});
        }
        return ids;
    }

    // Index path through `type`: each flat array's level indices become one flat index. Stops
    // early when the path ends inside a flat array (a row): `row` then holds that array, and
    // `row_base` the flat index of the row's first leaf.
    struct Path {
        std::vector<Index> indices;
        uint32_t type = 0;  // what the path reaches (the row's type when it stops at a row)
        const Flat* row = nullptr;
        Index row_base;
    };
    Path walk(SpirvBinary& out, uint32_t type, const std::vector<Index>& in) {
        Path p;
        if (!holds_flat(type, 0)) {  // nothing to flatten on this path
            p.indices = in;
            return p;
        }
        for (size_t i = 0; i < in.size();) {
            if (auto f = flat_.find(type); f != flat_.end()) {
                const size_t take = std::min(f->second.dims.size(), in.size() - i);
                const Index flat = combine(out, f->second, in, i, take);
                i += take;
                if (take < f->second.dims.size()) {
                    p.row = &f->second;
                    p.row_base = flat;
                    for (size_t k = 0; k < take; ++k) type = element(type);
                    p.type = type;
                    return p;
                }
                p.indices.push_back(flat);
                type = f->second.leaf;
                continue;
            }
            const Index& index = in[i++];
            p.indices.push_back(index);
            if (uint32_t e = element(type)) {
                type = e;
            } else if (auto s = f_.structs.find(type); s != f_.structs.end()) {
                if (!index.value || *index.value >= s->second.size()) refuse("a struct index it cannot read");
                type = s->second[*index.value];
            } else {
                type = component_of(type);
            }
        }
        p.type = type;
        return p;
    }
    uint32_t component_of(uint32_t type) const {
        for (const SpirvInstruction& in : list_)
            if ((in.opcode == spv::OpTypeVector || in.opcode == spv::OpTypeMatrix) && w_[in.offset + 1] == type) return w_[in.offset + 2];
        return 0;
    }
    // The flat index of levels [0, take) of `f` given by in[first...]: a known number when all are,
    // else computed (ids only: literal paths always know their numbers).
    Index combine(SpirvBinary& out, const Flat& f, const std::vector<Index>& in, size_t first, size_t take) {
        uint32_t known = 0;
        bool all_known = true;
        for (size_t k = 0; k < take; ++k) {
            if (in[first + k].value) known += *in[first + k].value * f.total(k + 1);
            else all_known = false;
        }
        const uint32_t type = in[first].type ? in[first].type : f.length_type;
        if (all_known) return {0, known, type};
        uint32_t sum = 0;
        for (size_t k = 0; k < take; ++k) {
            const Index& index = in[first + k];
            const uint32_t value = index.id ? index.id : constant(out, type, *index.value);
            uint32_t term = value;
            if (f.total(k + 1) != 1) {
                term = bound_++;
                append_instruction(out, spv::OpIMul, {type, term, value, constant(out, type, f.total(k + 1))});
            }
            if (sum == 0) {
                sum = term;
                continue;
            }
            const uint32_t next = bound_++;
            append_instruction(out, spv::OpIAdd, {type, next, sum, term});
            sum = next;
        }
        return {sum, std::nullopt, type};
    }
    // `base + t` as an index.
    Index offset(SpirvBinary& out, const Index& base, uint32_t t) {
        if (base.value) return {0, *base.value + t, base.type};
        if (t == 0) return base;
        const uint32_t id = bound_++;
        append_instruction(out, spv::OpIAdd, {base.type, id, base.id, constant(out, base.type, t)});
        return {id, std::nullopt, base.type};
    }

    std::vector<Index> ids_to_indices(const std::vector<uint32_t>& inst, size_t first) const {
        std::vector<Index> out;
        for (size_t i = first; i < inst.size(); ++i) {
            auto v = f_.int_values.find(inst[i]);
            out.push_back({inst[i], v == f_.int_values.end() ? std::nullopt : std::optional<uint32_t>(v->second), type_of(inst[i])});
        }
        return out;
    }
    static std::vector<Index> literals_to_indices(const std::vector<uint32_t>& inst, size_t first) {
        std::vector<Index> out;
        for (size_t i = first; i < inst.size(); ++i) out.push_back({0, inst[i]});
        return out;
    }
    std::vector<uint32_t> chain_operands(SpirvBinary& out, const std::vector<Index>& indices) {
        std::vector<uint32_t> ids;
        for (const Index& index : indices) ids.push_back(index.id ? index.id : constant(out, index.type, *index.value));
        return ids;
    }
    static std::vector<uint32_t> literal_operands(const std::vector<Index>& indices) {
        std::vector<uint32_t> out;
        for (const Index& index : indices) out.push_back(*index.value);
        return out;
    }

    // A pointer that stops at a row: never emitted; its base and index path wait for its uses.
    struct RowPointer {
        uint32_t base = 0, storage = 0;
        std::vector<Index> indices;  // the original, unflattened path from base
        uint32_t pointee = 0;        // the base pointer's pointee type
    };

    // Emits an access chain from `base` (pointee `pointee`) along `indices` (original form), typed
    // `result_type`, as `result`; when the path stops at a row, records it instead.
    void access_chain(SpirvBinary& out, spv::Op op, uint32_t result_type, uint32_t result, uint32_t base, uint32_t storage,
                      uint32_t pointee, const std::vector<Index>& indices) {
        Path p = walk(out, pointee, indices);
        if (p.row) {
            rows_[result] = {base, storage, indices, pointee};
            return;
        }
        std::vector<uint32_t> operands{result_type, result, base};
        const auto ids = chain_operands(out, p.indices);
        operands.insert(operands.end(), ids.begin(), ids.end());
        append_instruction(out, op, operands);
    }
    // The pointer to leaf t of a row pointer.
    uint32_t row_leaf_pointer(SpirvBinary& out, const RowPointer& row, uint32_t t) {
        Path p = walk(out, row.pointee, row.indices);
        std::vector<Index> indices = p.indices;
        indices.push_back(offset(out, p.row_base, t));
        const uint32_t id = bound_++;
        std::vector<uint32_t> operands{pointer_to(out, row.storage, p.row->leaf), id, row.base};
        const auto ids = chain_operands(out, indices);
        operands.insert(operands.end(), ids.begin(), ids.end());
        append_instruction(out, spv::OpAccessChain, operands);
        return id;
    }

    void rewrite(spv::Op op, std::vector<uint32_t>& inst, SpirvBinary& out) {
        auto keep = [&]() { out.insert(out.end(), inst.begin(), inst.end()); };
        switch (op) {
            case spv::OpTypeArray:
                if (auto f = flat_.find(inst[1]); f != flat_.end()) {
                    const uint32_t total = constant(out, f->second.length_type, f->second.total());
                    return append_instruction(out, spv::OpTypeArray, {inst[1], f->second.leaf, total});
                }
                return keep();
            case spv::OpConstantComposite:
            case spv::OpSpecConstantComposite:
            case spv::OpCompositeConstruct:
                if (flat_.count(inst[1])) {
                    if (op == spv::OpSpecConstantComposite) refuse("a specialisation constant array of arrays");
                    std::vector<uint32_t> operands{inst[1], inst[2]};
                    const uint32_t row = element(inst[1]);
                    for (size_t i = 3; i < inst.size(); ++i) {
                        std::vector<uint32_t> parts;
                        if (op == spv::OpCompositeConstruct) parts = value_leaves(out, inst[i], row);
                        else constant_leaves(out, inst[i], row, parts);
                        operands.insert(operands.end(), parts.begin(), parts.end());
                    }
                    return append_instruction(out, op, operands);
                }
                return keep();
            case spv::OpCompositeExtract: {  // type result composite literals...
                Path p = walk(out, type_of(inst[3]), literals_to_indices(inst, 4));
                if (!p.row) {
                    std::vector<uint32_t> operands{inst[1], inst[2], inst[3]};
                    const auto lits = literal_operands(p.indices);
                    operands.insert(operands.end(), lits.begin(), lits.end());
                    return append_instruction(out, op, operands);
                }
                std::vector<uint32_t> parts;
                for (uint32_t t = 0; t < leaves(p.type); ++t) {
                    std::vector<uint32_t> operands{p.row->leaf, bound_++, inst[3]};
                    const auto lits = literal_operands(p.indices);
                    operands.insert(operands.end(), lits.begin(), lits.end());
                    operands.push_back(*p.row_base.value + t);
                    parts.push_back(operands[1]);
                    append_instruction(out, op, operands);
                }
                std::vector<uint32_t> operands{inst[1], inst[2]};
                operands.insert(operands.end(), parts.begin(), parts.end());
                return append_instruction(out, spv::OpCompositeConstruct, operands);
            }
            case spv::OpCompositeInsert: {  // type result object composite literals...
                Path p = walk(out, inst[1], literals_to_indices(inst, 5));
                std::vector<uint32_t> lits = literal_operands(p.indices);
                if (!p.row) {
                    std::vector<uint32_t> operands{inst[1], inst[2], inst[3], inst[4]};
                    operands.insert(operands.end(), lits.begin(), lits.end());
                    return append_instruction(out, op, operands);
                }
                const std::vector<uint32_t> parts = value_leaves(out, inst[3], p.type);
                uint32_t into = inst[4];
                for (uint32_t t = 0; t < parts.size(); ++t) {
                    const uint32_t id = t + 1 == parts.size() ? inst[2] : bound_++;
                    std::vector<uint32_t> operands{inst[1], id, parts[t], into};
                    operands.insert(operands.end(), lits.begin(), lits.end());
                    operands.push_back(*p.row_base.value + t);
                    append_instruction(out, op, operands);
                    into = id;
                }
                return;
            }
            case spv::OpAccessChain:
            case spv::OpInBoundsAccessChain: {  // type result base ids...
                std::vector<Index> indices = ids_to_indices(inst, 4);
                uint32_t base = inst[3];
                if (auto row = rows_.find(base); row != rows_.end()) {  // a chain on from a row pointer
                    indices.insert(indices.begin(), row->second.indices.begin(), row->second.indices.end());
                    base = row->second.base;
                }
                auto pointer = f_.pointers.find(type_of(base));
                if (pointer == f_.pointers.end()) return keep();
                return access_chain(out, op, inst[1], inst[2], base, pointer->second.first, pointer->second.second, indices);
            }
            case spv::OpLoad:  // type result pointer [memory access]
                if (auto row = rows_.find(inst[3]); row != rows_.end()) {
                    std::vector<uint32_t> operands{inst[1], inst[2]};
                    for (uint32_t t = 0; t < leaves(inst[1]); ++t) {
                        const uint32_t leaf = bound_++, pointer = row_leaf_pointer(out, row->second, t);
                        append_instruction(out, spv::OpLoad, {leaf_of(inst[1]), leaf, pointer});
                        operands.push_back(leaf);
                    }
                    return append_instruction(out, spv::OpCompositeConstruct, operands);
                }
                return keep();
            case spv::OpStore:  // pointer object [memory access]
                if (auto row = rows_.find(inst[1]); row != rows_.end()) {
                    const std::vector<uint32_t> parts = value_leaves(out, inst[2], type_of(inst[2]));
                    for (uint32_t t = 0; t < parts.size(); ++t) append_instruction(out, spv::OpStore, {row_leaf_pointer(out, row->second, t), parts[t]});
                    return;
                }
                return keep();
            case spv::OpConstant:  // reusable from here on (a later one would be a forward reference)
                if (f_.int_values.count(inst[2])) constants_.emplace(std::make_pair(inst[1], inst[3]), inst[2]);
                return keep();
            default:
                if (hands_pointers_on(op))
                    for (size_t i = 1; i < inst.size(); ++i)
                        if (rows_.count(inst[i])) refuse("a pointer to a row passed on (only loads and stores through it are)");
                return keep();
        }
    }

    const SpirvBinary& w_;
    const std::vector<SpirvInstruction>& list_;
    SpirvFacts f_;  // the module as it was, and the constants and pointer types added since
    uint32_t bound_ = 0;
    bool in_functions_ = false;
    std::map<uint32_t, uint32_t> null_of_;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> constants_;  // {type, value} -> constant id
    std::map<uint32_t, Flat> flat_;
    std::map<uint32_t, RowPointer> rows_;
    SpirvBinary late_;
};

}  // namespace

size_t flatten_arrays_of_arrays(SpirvBinary& words) {
    if (words.size() < kSpirvHeaderWords || words[0] != spv::MagicNumber) return 0;
    const auto parsed = spirv_instructions(words);
    if (!parsed) return 0;
    Flattener flattener(words, *parsed);
    const size_t count = flattener.flat_count();
    if (count == 0) return 0;
    words = flattener.run();
    drop_annotations_of_missing_ids(words);  // the names of the values it replaced
    return count;
}

}  // namespace crtforge::detail
