// Struct stage inputs and outputs split into one variable per member, for Godot's shading language
// (its varyings are single values), WGSL (an inter-stage value is a scalar or a vector at a
// @location; a struct cannot be one) and GLSL ES (SPIRV-Cross splits them itself there, but drops
// the `flat` an int member must have).
//
// RetroArch's scanline-classic passes its timing model from the vertex to the fragment stage as one
// struct (`layout(location = 2) out TimebaseConfig tb;`, ten floats): 602 library presets.
// GLSL gives the members of a struct varying consecutive locations, starting at the variable's, so
// member k of a struct at location L lives at L plus the locations members 0..k-1 take. Splitting
// the variable into one per member at exactly those locations keeps the interface both stages agree
// on, and every other target reads the same locations. The module is rewritten once:
// - the variable is declared again as its leaf members' variables (before the first function, where
//   every pointer type they need is declared), with the variable's interpolation decorations;
// - an access chain into it starts at the member's variable (with no index left, an access chain
//   with no indices: the variable itself); one that stops at a nested struct is remembered;
// - a load of a (nested) struct loads its members, and builds the struct only where something
//   uses it whole (a member taken out of it is the member's load); a store stores the parts of a
//   struct built or constant there, or extracts them;
// - the struct types (and constants, pointers, function types of them) nothing refers to any more
//   are removed: SPIRV-Cross declares every struct type, and Godot 3 has no structs.
#include "targets/spirv_split_io_structs.hpp"

#include <spirv_cross/spirv.hpp>
#include <spirv_cross/spirv_cross_error_handling.hpp>
#include <spirv-tools/libspirv.h>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "generator/spirv_debug_names.hpp"
#include "generator/spirv_words.hpp"
#include "targets/spirv_facts.hpp"

namespace crtforge::detail {
namespace {

// One member of a split variable: a struct, whose members follow, or a leaf with its own variable.
struct Node {
    uint32_t type = 0;
    std::vector<Node> members;  // empty: a leaf
    uint32_t variable = 0, pointer_type = 0, location = 0;
    uint32_t split = 0;  // the variable split
    std::string name;
};

// The decorations a leaf takes over from its variable and the members on its path.
bool carried_decoration(uint32_t decoration) {
    switch (static_cast<spv::Decoration>(decoration)) {
        case spv::DecorationRelaxedPrecision:
        case spv::DecorationFlat:
        case spv::DecorationNoPerspective:
        case spv::DecorationCentroid:
        case spv::DecorationSample:
        case spv::DecorationInvariant: return true;
        default: return false;
    }
}

class Splitter {
public:
    Splitter(const SpirvBinary& w, const std::vector<SpirvInstruction>& list) : w_(w), list_(list) { gather(); }

    size_t split_count() const { return splits_.size(); }

    SpirvBinary run() {
        SpirvBinary out(w_.begin(), w_.begin() + kSpirvHeaderWords);
        bool declared = false;
        for (const SpirvInstruction& in : list_) {
            if (in.opcode == spv::OpFunction && !declared) {
                declare_leaves(out);
                declared = true;
            }
            if (!rewrite(in, out)) append_copy(out, w_, in);
        }
        if (!declared) declare_leaves(out);
        out[3] = bound_;
        drop_unused_struct_types(out);
        return out;
    }

private:
    [[noreturn]] void refuse(uint32_t variable, const std::string& what) const {
        auto n = names_.find(variable);
        const std::string name = n == names_.end() || n->second.empty() ? "#" + std::to_string(variable) : n->second;
        throw spirv_cross::CompilerError("the stage input/output struct '" + name + "' is split into its members for this target, but " + what);
    }

    uint32_t at(const SpirvInstruction& in, size_t i) const { return i < in.count ? w_[in.offset + i] : 0u; }

    void gather() {
        bound_ = w_[3];
        f_ = gather_spirv_facts(w_, list_);
        for (const SpirvInstruction& in : list_) {
            switch (in.opcode) {
                case spv::OpName: names_[at(in, 1)] = spirv_literal_string(w_, in.offset + 2, in.offset + in.count); break;
                case spv::OpMemberName:
                    member_names_[{at(in, 1), at(in, 2)}] = spirv_literal_string(w_, in.offset + 3, in.offset + in.count);
                    break;
                case spv::OpDecorate:
                    if (at(in, 2) == spv::DecorationLocation) locations_[at(in, 1)] = at(in, 3);
                    if (carried_decoration(at(in, 2)) && in.count == 3) decorations_[at(in, 1)].push_back(at(in, 2));
                    break;
                case spv::OpMemberDecorate:
                    if (at(in, 3) == spv::DecorationLocation) member_locations_[{at(in, 1), at(in, 2)}] = at(in, 4);
                    if (carried_decoration(at(in, 3)) && in.count == 4) member_decorations_[{at(in, 1), at(in, 2)}].push_back(at(in, 3));
                    break;
                case spv::OpTypeFloat:
                case spv::OpTypeInt: widths_[at(in, 1)] = at(in, 2); break;
                default: break;
            }
        }
        for (const SpirvInstruction& in : list_) {
            if (in.opcode == spv::OpFunction) break;
            if (in.opcode != spv::OpVariable) continue;
            const uint32_t variable = at(in, 2), storage = at(in, 3);
            if (storage != spv::StorageClassInput && storage != spv::StorageClassOutput) continue;
            auto pointer = f_.pointers.find(at(in, 1));
            if (pointer == f_.pointers.end()) continue;
            const uint32_t type = pointer->second.second;
            if (!holds_plain_struct(type)) continue;
            if (!f_.structs.count(type)) refuse(variable, "not an array of structs");
            auto location = locations_.find(variable);
            if (location == locations_.end()) refuse(variable, "it has no location");
            Node root;
            root.type = type;
            root.split = variable;
            root.name = names_.count(variable) ? names_.at(variable) : "";
            uint32_t next_location = location->second;
            build(variable, root, storage, next_location, decorations_[variable]);
            splits_[variable] = std::move(root);
            split_storage_[variable] = storage;
        }
        for (auto& [variable, root] : splits_) pointer_nodes_[variable] = &root;
        if (!splits_.empty()) find_uses();
    }

    // Where the split variables are reached, and which whole-struct values need not be built:
    // a loaded struct whose every use takes a member out (the member's load stands in), a built
    // struct whose every use stores it into a split variable (its parts are stored). Godot 3 has
    // no structs, so a struct the varyings no longer need must not be left in the code.
    void find_uses() {
        std::map<uint32_t, size_t> uses, extracted, stored;
        bool in_functions = false;
        for (const SpirvInstruction& in : list_) {
            in_functions = in_functions || in.opcode == spv::OpFunction;
            if (!in_functions) continue;
            bool has_result = false, has_type = false;
            spv::HasResultAndType(static_cast<spv::Op>(in.opcode), &has_result, &has_type);
            for (size_t i = 1 + (has_type ? 1 : 0) + (has_result ? 1 : 0); i < in.count; ++i) ++uses[at(in, i)];
            switch (in.opcode) {
                case spv::OpAccessChain:
                case spv::OpInBoundsAccessChain: {
                    const Node* node = node_of(at(in, 3));
                    if (!node) break;
                    size_t i = 4;
                    node = walk(node, in, i);
                    if (!node->members.empty()) pointer_nodes_[at(in, 2)] = node;
                    break;
                }
                case spv::OpLoad:
                    if (const Node* node = node_of(at(in, 3)); node && !node->members.empty()) loaded_[at(in, 2)] = node;
                    break;
                case spv::OpCompositeConstruct:  // of a struct: its parts can be stored one by one
                    if (f_.structs.count(at(in, 1)))
                        constructs_[at(in, 2)] = {w_.begin() + static_cast<long>(in.offset + 3), w_.begin() + static_cast<long>(in.offset + in.count)};
                    break;
                case spv::OpCompositeExtract: {
                    auto load = loaded_.find(at(in, 3));
                    if (load == loaded_.end()) break;
                    size_t i = 4;
                    const Node* node = walk_value(load->second, in, i);
                    if (!node) break;
                    ++extracted[at(in, 3)];
                    if (!node->members.empty()) loaded_[at(in, 2)] = node;  // a nested struct: its uses in turn
                    break;
                }
                case spv::OpStore:
                    if (const Node* node = node_of(at(in, 1)); node && !node->members.empty() && constructs_.count(at(in, 2)))
                        ++stored[at(in, 2)];
                    break;
                default: break;
            }
        }
        for (const auto& [load, node] : loaded_)
            if (uses[load] == extracted[load]) unbuilt_loads_.insert(load);
        // A built struct stored part by part: its parts that are built structs used nowhere else
        // are stored part by part too.
        std::function<void(uint32_t)> unbuilt = [&](uint32_t construct) {
            if (!unbuilt_constructs_.insert(construct).second) return;
            for (uint32_t part : constructs_.at(construct))
                if (constructs_.count(part) && uses[part] == 1) unbuilt(part);
        };
        for (const auto& [construct, count] : stored)
            if (uses[construct] == count) unbuilt(construct);
    }

    // Down an access chain's constant indices (from operand `i`) while they name struct members.
    const Node* walk(const Node* node, const SpirvInstruction& in, size_t& i) const {
        for (; i < in.count && !node->members.empty(); ++i) {
            auto index = f_.int_values.find(at(in, i));
            if (index == f_.int_values.end() || index->second >= node->members.size())
                refuse(node->split, "not a member index that is not a constant");
            node = &node->members[index->second];
        }
        return node;
    }

    // Down a composite extract's literal indices (from operand `i`) to a leaf or a nested struct
    // (nullptr: an index past the members).
    static const Node* walk_value(const Node* node, const SpirvInstruction& in, size_t& i, const SpirvBinary& w) {
        for (; i < in.count && !node->members.empty(); ++i) {
            const uint32_t index = w[in.offset + i];
            if (index >= node->members.size()) return nullptr;
            node = &node->members[index];
        }
        return node;
    }
    const Node* walk_value(const Node* node, const SpirvInstruction& in, size_t& i) const { return walk_value(node, in, i, w_); }

    // A struct that is not a block, or an array of them: what this pass splits (or refuses).
    bool holds_plain_struct(uint32_t type) const {
        if (f_.structs.count(type)) return !f_.blocks.count(type);
        if (const uint32_t element = f_.element(type)) return holds_plain_struct(element);
        return false;
    }

    // How many locations a value of `type` takes (GLSL's rules: a 64-bit vector of 3 or 4, two).
    uint32_t locations_of(uint32_t variable, uint32_t type) const {
        if (auto v = f_.vectors.find(type); v != f_.vectors.end())
            return widths_.count(v->second.first) && widths_.at(v->second.first) == 64 && v->second.second > 2 ? 2 : 1;
        if (auto m = f_.matrices.find(type); m != f_.matrices.end()) return m->second.second * locations_of(variable, m->second.first);
        if (auto a = f_.arrays.find(type); a != f_.arrays.end()) {
            auto length = f_.int_values.find(a->second.second);
            if (length == f_.int_values.end()) refuse(variable, "a member array's length is not a constant");
            return length->second * locations_of(variable, a->second.first);
        }
        if (auto s = f_.structs.find(type); s != f_.structs.end()) {
            uint32_t sum = 0;
            for (uint32_t member : s->second) sum += locations_of(variable, member);
            return sum;
        }
        return 1;  // a scalar
    }

    void build(uint32_t variable, Node& node, uint32_t storage, uint32_t& location, const std::vector<uint32_t>& inherited) {
        const std::vector<uint32_t>& members = f_.structs.at(node.type);
        for (uint32_t k = 0; k < members.size(); ++k) {
            Node member;
            member.type = members[k];
            member.split = variable;
            auto member_name = member_names_.find({node.type, k});
            const std::string part = member_name != member_names_.end() && !member_name->second.empty() ? member_name->second
                                                                                                          : "m" + std::to_string(k);
            member.name = (node.name.empty() ? "io" : node.name) + "_" + part;
            if (auto explicit_location = member_locations_.find({node.type, k}); explicit_location != member_locations_.end())
                location = explicit_location->second;
            std::vector<uint32_t> decorations = inherited;
            if (auto d = member_decorations_.find({node.type, k}); d != member_decorations_.end())
                decorations.insert(decorations.end(), d->second.begin(), d->second.end());
            if (f_.structs.count(member.type)) {
                build(variable, member, storage, location, decorations);
            } else {
                if (holds_plain_struct(member.type)) refuse(variable, "not a member that is an array of structs");
                member.variable = bound_++;
                member.location = location;
                member.pointer_type = pointer_type(storage, member.type);
                location += locations_of(variable, member.type);
                leaf_decorations_[member.variable] = decorations;
            }
            node.members.push_back(std::move(member));
        }
    }

    // The module's pointer type to `type` in `storage`, or a new one declared with the leaves.
    uint32_t pointer_type(uint32_t storage, uint32_t type) {
        for (const auto& [id, pointer] : f_.pointers)
            if (pointer.first == storage && pointer.second == type) return id;
        auto made = new_pointers_.find({storage, type});
        if (made != new_pointers_.end()) return made->second;
        return new_pointers_[{storage, type}] = bound_++;
    }

    template <typename Visit>
    static void each_leaf(const Node& node, Visit&& visit) {
        if (node.members.empty()) {
            visit(node);
            return;
        }
        for (const Node& member : node.members) each_leaf(member, visit);
    }

    void declare_leaves(SpirvBinary& out) const {
        for (const auto& [key, id] : new_pointers_) append_instruction(out, spv::OpTypePointer, {id, key.first, key.second});
        for (const auto& [variable, root] : splits_)
            each_leaf(root, [&](const Node& leaf) {
                append_instruction(out, spv::OpVariable, {leaf.pointer_type, leaf.variable, split_storage_.at(variable)});
            });
    }

    // The split structs' types (and pointer types to them) nothing refers to any more, removed
    // with their names and decorations: SPIRV-Cross declares every struct type of a module, and
    // Godot 3 has no structs.
    void drop_unused_struct_types(SpirvBinary& words) const {
        std::set<uint32_t> candidates;
        std::function<void(const Node&)> collect = [&](const Node& node) {
            if (node.members.empty()) return;
            candidates.insert(node.type);
            for (const Node& member : node.members) collect(member);
        };
        for (const auto& [variable, root] : splits_) collect(root);
        for (const auto& [id, pointer] : f_.pointers)
            if (candidates.count(pointer.second)) candidates.insert(id);
        for (bool dropped = true; dropped;) {
            dropped = false;
            auto list = spirv_instructions(words);
            if (!list) return;
            auto annotation = [](uint32_t opcode) {
                return opcode == spv::OpName || opcode == spv::OpMemberName || opcode == spv::OpDecorate || opcode == spv::OpMemberDecorate;
            };
            auto result_word = [](const SpirvInstruction& in) -> size_t {
                bool has_result = false, has_type = false;
                spv::HasResultAndType(static_cast<spv::Op>(in.opcode), &has_result, &has_type);
                return has_result ? (has_type ? 2 : 1) : 0;
            };
            // A type or constant made of a split struct type (a constant of it, a pointer or an
            // array of it, a function type of such pointers that inlining left) goes with it
            // once nothing refers to it.
            for (const SpirvInstruction& in : *list) {
                const size_t result = result_word(in);
                const bool constant = in.opcode == spv::OpConstantComposite || in.opcode == spv::OpConstantNull || in.opcode == spv::OpUndef;
                const bool type = in.opcode == spv::OpTypePointer || in.opcode == spv::OpTypeFunction || in.opcode == spv::OpTypeArray ||
                                  in.opcode == spv::OpTypeRuntimeArray || in.opcode == spv::OpTypeStruct;
                if ((constant || type) && result != 0)
                    for (size_t i = 1; i < in.count; ++i)
                        if (i != result && candidates.count(words[in.offset + i])) candidates.insert(words[in.offset + result]);
            }
            const std::map<uint32_t, size_t> references = id_references(words);
            if (references.count(0)) return;  // the module did not parse: keep every type
            std::set<uint32_t> unused;
            for (uint32_t id : candidates)
                if (!references.count(id)) unused.insert(id);
            if (unused.empty()) return;
            for (uint32_t id : unused) candidates.erase(id);
            rewrite_instructions(words, *list, [&](const SpirvInstruction& in, SpirvBinary&, uint32_t&) {
                const size_t at = annotation(in.opcode) ? 1 : result_word(in);
                return at != 0 && at < in.count && unused.count(words[in.offset + at]) != 0;
            });
            dropped = true;
        }
    }

    // How often each id is an operand (not a result) of an instruction other than a name or a
    // decoration, by SPIRV-Tools' grammar (a literal that equals an id does not count). Empty where
    // the module does not parse: then nothing is dropped.
    static std::map<uint32_t, size_t> id_references(const SpirvBinary& words) {
        struct Count {
            std::map<uint32_t, size_t> references;
            bool ok = true;
        } count;
        spv_context context = spvContextCreate(SPV_ENV_UNIVERSAL_1_6);
        const spv_result_t parsed = spvBinaryParse(
            context, &count, words.data(), words.size(), nullptr,
            [](void* user, const spv_parsed_instruction_t* in) -> spv_result_t {
                auto& c = *static_cast<Count*>(user);
                switch (static_cast<spv::Op>(in->opcode)) {
                    case spv::OpName: case spv::OpMemberName: case spv::OpDecorate: case spv::OpMemberDecorate:
                    case spv::OpDecorateString: case spv::OpMemberDecorateString: return SPV_SUCCESS;
                    default: break;
                }
                for (uint16_t i = 0; i < in->num_operands; ++i) {
                    const spv_parsed_operand_t& o = in->operands[i];
                    if (o.type == SPV_OPERAND_TYPE_ID || o.type == SPV_OPERAND_TYPE_TYPE_ID || o.type == SPV_OPERAND_TYPE_SCOPE_ID ||
                        o.type == SPV_OPERAND_TYPE_MEMORY_SEMANTICS_ID)
                        ++c.references[in->words[o.offset]];
                }
                return SPV_SUCCESS;
            },
            nullptr);
        spvContextDestroy(context);
        if (parsed != SPV_SUCCESS) return {{0, 0}};  // a marker: refer to everything (see below)
        return count.references;
    }

    // The id a pointer operand names, as a node of a split variable (nullptr: not one).
    const Node* node_of(uint32_t id) const {
        auto n = pointer_nodes_.find(id);
        return n == pointer_nodes_.end() ? nullptr : n->second;
    }

    // Loads `node`'s leaves (their ids kept in `leaves`) and, where `build`, the value of `node`.
    void load(const Node& node, uint32_t result, bool build, std::map<uint32_t, uint32_t>& leaves, SpirvBinary& out) {
        if (node.members.empty()) {
            append_instruction(out, spv::OpLoad, {node.type, result, node.variable});
            leaves[node.variable] = result;
            return;
        }
        std::vector<uint32_t> operands = {node.type, result};
        for (const Node& member : node.members) {
            const uint32_t part = bound_++;
            load(member, part, build, leaves, out);
            operands.push_back(part);
        }
        if (build) append_instruction(out, spv::OpCompositeConstruct, operands);
    }

    // `node`'s value built from its leaves' loads.
    void build(const Node& node, uint32_t result, const std::map<uint32_t, uint32_t>& leaves, SpirvBinary& out) {
        std::vector<uint32_t> operands = {node.type, result};
        for (const Node& member : node.members) {
            if (member.members.empty()) {
                operands.push_back(leaves.at(member.variable));
                continue;
            }
            const uint32_t part = bound_++;
            build(member, part, leaves, out);
            operands.push_back(part);
        }
        append_instruction(out, spv::OpCompositeConstruct, operands);
    }

    void store(const Node& node, uint32_t value, SpirvBinary& out) {
        if (node.members.empty()) {
            append_instruction(out, spv::OpStore, {node.variable, value});
            return;
        }
        // A value built here or a constant: its parts are known, and stored as they are.
        const std::vector<uint32_t>* parts = nullptr;
        if (auto built = constructs_.find(value); built != constructs_.end()) parts = &built->second;
        if (auto constant = f_.constant_composites.find(value); constant != f_.constant_composites.end()) parts = &constant->second;
        const bool parts_known = parts && parts->size() == node.members.size();
        for (uint32_t k = 0; k < node.members.size(); ++k) {
            uint32_t part = parts_known ? (*parts)[k] : 0;
            if (!parts_known) {
                part = bound_++;
                append_instruction(out, spv::OpCompositeExtract, {node.members[k].type, part, value, k});
            }
            store(node.members[k], part, out);
        }
    }

    // Appends what replaces `in` and returns true, or returns false to keep it.
    bool rewrite(const SpirvInstruction& in, SpirvBinary& out) {
        switch (in.opcode) {
            case spv::OpEntryPoint: {
                size_t first_interface = 3;
                while (first_interface < in.count && (w_[in.offset + first_interface] >> 24) != 0) ++first_interface;
                ++first_interface;  // past the word holding the name's terminating nul
                std::vector<uint32_t> operands(w_.begin() + static_cast<long>(in.offset + 1),
                                               w_.begin() + static_cast<long>(in.offset + std::min<size_t>(first_interface, in.count)));
                bool changed = false;
                for (size_t i = first_interface; i < in.count; ++i) {
                    auto split = splits_.find(at(in, i));
                    if (split == splits_.end()) {
                        operands.push_back(at(in, i));
                        continue;
                    }
                    changed = true;
                    each_leaf(split->second, [&](const Node& leaf) { operands.push_back(leaf.variable); });
                }
                if (!changed) return false;
                append_instruction(out, in.opcode, operands);
                return true;
            }
            case spv::OpName: {
                auto split = splits_.find(at(in, 1));
                if (split == splits_.end()) return false;
                each_leaf(split->second, [&](const Node& leaf) { append_name(out, leaf.variable, leaf.name); });
                return true;
            }
            case spv::OpDecorate: {
                auto split = splits_.find(at(in, 1));
                if (split == splits_.end()) return false;
                if (at(in, 2) != spv::DecorationLocation) return true;  // carried (or dropped) with the location
                each_leaf(split->second, [&](const Node& leaf) {
                    append_instruction(out, spv::OpDecorate, {leaf.variable, spv::DecorationLocation, leaf.location});
                    std::set<uint32_t> done;
                    for (uint32_t d : leaf_decorations_.at(leaf.variable))
                        if (done.insert(d).second) append_instruction(out, spv::OpDecorate, {leaf.variable, d});
                });
                return true;
            }
            case spv::OpVariable: return splits_.count(at(in, 2)) != 0;  // declared again as its leaves
            case spv::OpAccessChain:
            case spv::OpInBoundsAccessChain: {
                const Node* node = node_of(at(in, 3));
                if (!node) return false;
                size_t i = 4;
                node = walk(node, in, i);
                if (!node->members.empty()) return true;  // stops at a nested struct: its uses are rewritten
                std::vector<uint32_t> operands = {at(in, 1), at(in, 2), node->variable};
                for (; i < in.count; ++i) operands.push_back(at(in, i));
                append_instruction(out, in.opcode, operands);
                return true;
            }
            case spv::OpCompositeConstruct: return unbuilt_constructs_.count(at(in, 2)) != 0;  // stored part by part
            case spv::OpCompositeExtract: {
                auto leaves = loaded_leaves_.find(at(in, 3));
                if (leaves == loaded_leaves_.end()) return false;
                size_t i = 4;
                const Node* leaf = walk_value(loaded_.at(at(in, 3)), in, i);
                if (!leaf) return false;
                if (!leaf->members.empty()) {  // a nested struct: its members' loads, built only where needed
                    std::map<uint32_t, uint32_t>& nested = loaded_leaves_[at(in, 2)];
                    each_leaf(*leaf, [&](const Node& l) { nested[l.variable] = leaves->second.at(l.variable); });
                    if (!unbuilt_loads_.count(at(in, 2))) build(*leaf, at(in, 2), nested, out);
                    return true;
                }
                const uint32_t part = leaves->second.at(leaf->variable);
                if (i == in.count) {
                    append_instruction(out, spv::OpCopyObject, {at(in, 1), at(in, 2), part});
                    return true;
                }
                std::vector<uint32_t> operands = {at(in, 1), at(in, 2), part};
                for (; i < in.count; ++i) operands.push_back(at(in, i));
                append_instruction(out, spv::OpCompositeExtract, operands);
                return true;
            }
            case spv::OpLoad: {
                const Node* node = node_of(at(in, 3));
                if (!node) return false;
                load(*node, at(in, 2), !unbuilt_loads_.count(at(in, 2)), loaded_leaves_[at(in, 2)], out);
                return true;
            }
            case spv::OpStore: {
                const Node* node = node_of(at(in, 1));
                if (!node) return false;
                store(*node, at(in, 2), out);
                return true;
            }
            default: break;
        }
        if (hands_pointers_on(in.opcode) || in.opcode == spv::OpPtrEqual || in.opcode == spv::OpPtrNotEqual)
            for (size_t i = 1; i < in.count; ++i)
                if (const Node* node = node_of(at(in, i)))
                    refuse(node->split, "not as a pointer handed to a call, a copy or a choice");
        return false;
    }

    static void append_name(SpirvBinary& out, uint32_t id, const std::string& name) {
        std::vector<uint32_t> operands = {id};
        for (size_t i = 0; i <= name.size(); i += 4) {
            uint32_t word = 0;
            for (size_t b = 0; b < 4 && i + b < name.size(); ++b) word |= static_cast<uint32_t>(static_cast<unsigned char>(name[i + b])) << (8 * b);
            operands.push_back(word);
        }
        append_instruction(out, spv::OpName, operands);
    }

    const SpirvBinary& w_;
    const std::vector<SpirvInstruction>& list_;
    SpirvFacts f_;
    uint32_t bound_ = 0;
    std::map<uint32_t, std::string> names_;
    std::map<std::pair<uint32_t, uint32_t>, std::string> member_names_;
    std::map<uint32_t, uint32_t> locations_, widths_;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> member_locations_;
    std::map<uint32_t, std::vector<uint32_t>> decorations_, leaf_decorations_;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> member_decorations_;
    std::map<uint32_t, Node> splits_;  // split variable -> its members
    std::map<uint32_t, uint32_t> split_storage_;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> new_pointers_;  // {storage, type} -> new pointer type
    std::map<uint32_t, const Node*> pointer_nodes_;  // a split variable or a chain into it -> its node
    std::map<uint32_t, const Node*> loaded_;         // a load of a (nested) struct of a split variable -> its node
    std::map<uint32_t, std::map<uint32_t, uint32_t>> loaded_leaves_;  // that load -> leaf variable -> its load
    std::map<uint32_t, std::vector<uint32_t>> constructs_;  // OpCompositeConstruct of a struct -> its constituents
    std::set<uint32_t> unbuilt_loads_, unbuilt_constructs_;
};

}  // namespace

size_t split_interface_structs(SpirvBinary& words) {
    auto list = spirv_instructions(words);
    if (!list) return 0;
    Splitter splitter(words, *list);
    if (splitter.split_count() == 0) return 0;
    words = splitter.run();
    drop_annotations_of_missing_ids(words);  // of the loads and values no longer built
    return splitter.split_count();
}

}  // namespace crtforge::detail
