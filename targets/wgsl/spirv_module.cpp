#include "targets/wgsl/spirv_module.hpp"

#include <fmt/format.h>
#include <spirv-tools/libspirv.h>

namespace crtforge::wgsl {

namespace {

// A literal string operand starting at word `first`: bytes in little-endian order, NUL-terminated.
std::string read_string(const std::vector<uint32_t>& words, size_t first) {
    std::string out;
    for (size_t i = first; i < words.size(); ++i) {
        for (int b = 0; b < 4; ++b) {
            char c = static_cast<char>((words[i] >> (8 * b)) & 0xffu);
            if (c == '\0') return out;
            out += c;
        }
    }
    return out;
}

// The operand words from index `first` on: none when a malformed instruction is shorter.
std::vector<uint32_t> words_from(const std::vector<uint32_t>& w, size_t first) {
    return first < w.size() ? std::vector<uint32_t>(w.begin() + static_cast<long>(first), w.end()) : std::vector<uint32_t>{};
}

// What makes a type declaration unusable, or "" when there is nothing. A valid module declares each
// type once, after the types it refers to, so the emitter's recursive walks over types end; malformed
// input could make a cycle, or a vector whose layout has no size.
std::string type_problem(const SpirvModule& m, uint32_t id, const Type& t) {
    if (m.types.count(id)) return fmt::format("type %{} is declared twice", id);
    std::vector<uint32_t> refers = t.members;
    if (t.element) refers.push_back(t.element);
    for (uint32_t other : refers)
        if (!m.types.count(other)) return fmt::format("type %{} refers to %{}, which is not a type declared before it", id, other);
    const spv::Op element = m.type(t.element).op;
    const bool scalar = element == spv::OpTypeFloat || element == spv::OpTypeInt || element == spv::OpTypeBool;
    if (t.op == spv::OpTypeVector && (t.count < 2 || t.count > 4 || !scalar))
        return fmt::format("type %{} is not a vector of 2 to 4 scalars", id);
    if (t.op == spv::OpTypeMatrix && (t.count < 2 || t.count > 4 || element != spv::OpTypeVector))
        return fmt::format("type %{} is not a matrix of 2 to 4 vectors", id);
    return {};
}

bool is_terminator(spv::Op op) {
    switch (op) {
        case spv::OpBranch: case spv::OpBranchConditional: case spv::OpSwitch: case spv::OpReturn:
        case spv::OpReturnValue: case spv::OpKill: case spv::OpUnreachable: case spv::OpTerminateInvocation:
            return true;
        default: return false;
    }
}

void apply_decoration(Decorations& d, spv::Decoration decoration, const std::vector<uint32_t>& args) {
    auto arg = [&](size_t i) { return i < args.size() ? args[i] : 0u; };
    switch (decoration) {
        case spv::DecorationBinding: d.binding = arg(0); break;
        case spv::DecorationDescriptorSet: d.set = arg(0); break;
        case spv::DecorationLocation: d.location = arg(0); break;
        case spv::DecorationOffset: d.offset = arg(0); break;
        case spv::DecorationArrayStride: d.array_stride = arg(0); break;
        case spv::DecorationBuiltIn: d.builtin = operand_enum(arg(0), spv::BuiltInMax); break;
        case spv::DecorationBlock: d.block = true; break;
        case spv::DecorationFlat: d.flat = true; break;
        case spv::DecorationNoPerspective: d.no_perspective = true; break;
        case spv::DecorationCentroid: d.centroid = true; break;
        case spv::DecorationSample: d.sample = true; break;
        default: break;  // RelaxedPrecision is tracked separately; the rest do not change the WGSL
    }
}

}  // namespace

std::string opcode_name(spv::Op op) {
    return std::string("Op") + spvOpcodeString(static_cast<uint32_t>(op));
}

const Type& SpirvModule::type(uint32_t id) const {
    static const Type none;
    auto it = types.find(id);
    return it == types.end() ? none : it->second;
}

const Function* SpirvModule::function(uint32_t id) const {
    for (const auto& f : functions)
        if (f.id == id) return &f;
    return nullptr;
}

std::string SpirvModule::name(uint32_t id) const {
    auto it = names.find(id);
    return it == names.end() ? std::string() : it->second;
}

Result<SpirvModule> parse_spirv(const SpirvBinary& words) {
    if (words.size() < 5 || words[0] != spv::MagicNumber)
        return make_validation_error("WGSL emitter: not a SPIR-V module (bad header)");
    SpirvModule m;
    std::map<uint32_t, std::string> strings;  // OpString ids, for OpLine
    Function* function = nullptr;
    Block* block = nullptr;
    SourceLine line;

    for (size_t at = 5; at < words.size();) {
        const uint32_t count = words[at] >> 16;
        const auto op = static_cast<spv::Op>(words[at] & 0xffffu);
        if (count == 0 || at + count > words.size())
            return make_validation_error(fmt::format("WGSL emitter: truncated SPIR-V instruction at word {}", at));
        std::vector<uint32_t> w(words.begin() + static_cast<long>(at) + 1, words.begin() + static_cast<long>(at + count));
        at += count;

        Instruction inst;
        inst.op = op;
        bool has_result = false, has_type = false;
        spv::HasResultAndType(op, &has_result, &has_type);
        size_t first = 0;
        if (has_type) inst.type = w.at(first++);
        if (has_result) inst.result = first < w.size() ? w[first++] : 0;
        inst.operands.assign(w.begin() + static_cast<long>(std::min(first, w.size())), w.end());
        inst.line = line;

        switch (op) {
            case spv::OpString: strings[w.at(0)] = read_string(w, 1); continue;
            case spv::OpLine: line = {strings.count(w.at(0)) ? strings[w.at(0)] : std::string(), static_cast<int>(w.at(1))}; continue;
            case spv::OpNoLine: line = {}; continue;
            case spv::OpName: m.names[w.at(0)] = read_string(w, 1); continue;
            case spv::OpMemberName: m.member_names[{w.at(0), w.at(1)}] = read_string(w, 2); continue;
            case spv::OpExtInstImport: m.ext_imports[w.at(0)] = read_string(w, 1); continue;
            case spv::OpEntryPoint: {
                EntryPoint e;
                e.model = operand_enum(w.at(0), spv::ExecutionModelMax);
                e.function = w.at(1);
                e.name = read_string(w, 2);
                const size_t name_words = e.name.size() / 4 + 1;
                for (size_t i = 2 + name_words; i < w.size(); ++i) e.interface.push_back(w[i]);
                m.entry_points.push_back(std::move(e));
                continue;
            }
            case spv::OpExecutionMode: m.execution_modes.insert(operand_enum(w.at(1), spv::ExecutionModeMax)); continue;
            case spv::OpDecorate: {
                const auto decoration = operand_enum(w.at(1), spv::DecorationMax);
                if (decoration == spv::DecorationRelaxedPrecision) m.relaxed_precision.insert(w.at(0));
                apply_decoration(m.decorations[w.at(0)], decoration, words_from(w, 2));
                continue;
            }
            case spv::OpMemberDecorate:
                apply_decoration(m.member_decorations[{w.at(0), w.at(1)}], operand_enum(w.at(2), spv::DecorationMax),
                                 words_from(w, 3));
                continue;
            case spv::OpCapability: case spv::OpExtension: case spv::OpMemoryModel: case spv::OpSource:
            case spv::OpSourceExtension: case spv::OpSourceContinued: case spv::OpModuleProcessed: case spv::OpNop:
                continue;
            default: break;
        }

        // Types.
        if (op >= spv::OpTypeVoid && op <= spv::OpTypeForwardPointer && op != spv::OpTypeForwardPointer) {
            Type t;
            t.op = op;
            switch (op) {
                case spv::OpTypeInt: t.width = w.at(1); t.is_signed = w.at(2) != 0; break;
                case spv::OpTypeFloat: t.width = w.at(1); break;
                case spv::OpTypeVector: case spv::OpTypeMatrix: t.element = w.at(1); t.count = w.at(2); break;
                case spv::OpTypeArray: {
                    t.element = w.at(1);
                    auto c = m.constants.find(w.at(2));
                    if (c == m.constants.end() || c->second.words.empty())
                        return make_validation_error("WGSL emitter: array length is not a constant");
                    t.count = c->second.words[0];
                    break;
                }
                case spv::OpTypeRuntimeArray: t.element = w.at(1); break;
                case spv::OpTypeStruct: t.members = words_from(w, 1); break;
                case spv::OpTypePointer: t.storage = operand_enum(w.at(1), spv::StorageClassMax); t.element = w.at(2); break;
                case spv::OpTypeFunction: t.members = words_from(w, 1); break;
                case spv::OpTypeImage:
                    t.element = w.at(1);
                    t.dim = operand_enum(w.at(2), spv::DimMax);
                    t.depth = w.at(3) == 1;
                    t.arrayed = w.at(4) != 0;
                    t.multisampled = w.at(5) != 0;
                    break;
                case spv::OpTypeSampledImage: t.element = w.at(1); break;
                default: break;
            }
            if (const std::string problem = type_problem(m, w.at(0), t); !problem.empty())
                return make_validation_error("WGSL emitter: " + problem, line.file, line.line);
            m.types[w.at(0)] = t;
            continue;
        }

        // Constants (OpUndef outside functions is a constant too: any value will do, we use zero).
        if (!function && (op == spv::OpConstant || op == spv::OpConstantComposite || op == spv::OpConstantTrue ||
                          op == spv::OpConstantFalse || op == spv::OpConstantNull || op == spv::OpUndef)) {
            // As for types: a composite made of constants declared before it cannot contain itself.
            if (m.constants.count(inst.result))
                return make_validation_error(fmt::format("WGSL emitter: constant %{} is declared twice", inst.result),
                                             line.file, line.line);
            if (op == spv::OpConstantComposite)
                for (uint32_t part : inst.operands)
                    if (!m.constants.count(part))
                        return make_validation_error(fmt::format(
                            "WGSL emitter: constant %{} uses %{}, which is not a constant declared before it", inst.result, part),
                            line.file, line.line);
            m.constants[inst.result] = {inst.type, op, inst.operands};
            continue;
        }
        if (!function && op == spv::OpVariable) {
            m.globals[inst.result] = inst;
            continue;
        }

        switch (op) {
            case spv::OpFunction:
                m.functions.emplace_back();
                function = &m.functions.back();
                function->id = inst.result;
                function->return_type = inst.type;
                function->function_type = inst.operand(1);
                continue;
            case spv::OpFunctionParameter:
                if (!function) break;
                function->params.push_back(inst);
                continue;
            case spv::OpFunctionEnd:
                function = nullptr;
                block = nullptr;
                line = {};
                continue;
            case spv::OpLabel:
                if (!function) break;
                function->block_index[inst.result] = function->blocks.size();
                function->blocks.emplace_back();
                block = &function->blocks.back();
                block->label = inst.result;
                continue;
            default: break;
        }

        if (!block) {
            // Module-scope instructions we do not model (spec constants, OpTypeForwardPointer, ...).
            return make_validation_error(fmt::format("WGSL emitter: cannot translate {} at module scope", opcode_name(op)),
                                         line.file, line.line);
        }
        if (op == spv::OpVariable) function->variables.push_back(inst);
        else if (op == spv::OpPhi) block->phis.push_back(inst);
        else if (op == spv::OpSelectionMerge || op == spv::OpLoopMerge) block->merge = inst;
        else if (is_terminator(op)) { block->terminator = inst; block = nullptr; }
        else block->body.push_back(inst);
    }
    if (m.entry_points.empty()) return make_validation_error("WGSL emitter: the module has no entry point");
    return m;
}

}  // namespace crtforge::wgsl
