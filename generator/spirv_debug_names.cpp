// Template names for the optimiser's SSA values, then the debug info that carried them removed.
//
// spirv-opt inlines every stage function and promotes locals to SSA values, and the OpNames of
// those locals die with them: SPIRV-Cross then prints `vec2 _342`. glslang's NonSemantic shader
// debug info survives the optimiser instead: ssa-rewrite turns each DebugDeclare of a local into a
// DebugValue naming the SSA value the local holds at that point, through inlining. Here each such
// value gets the local's name as an OpName (the first name wins), and then every trace of the debug
// info is removed, so the module that leaves the generator is the one the optimiser made, plus names.
#include "generator/spirv_debug_names.hpp"
#include "generator/spirv_words.hpp"

#include <map>
#include <set>
#include <string>
#include <string_view>

#include <glslang/SPIRV/NonSemanticShaderDebugInfo100.h>
#include <glslang/SPIRV/spirv.hpp>

namespace crtforge {
namespace {

using detail::spirv_literal_string;
using Instruction = detail::SpirvInstruction;

void append_string(SpirvBinary& out, const std::string& text) {
    const size_t words = text.size() / 4 + 1;  // always room for the terminating zero
    const size_t first = out.size();
    out.resize(first + words, 0u);
    for (size_t i = 0; i < text.size(); ++i)
        out[first + i / 4] |= static_cast<uint32_t>(static_cast<unsigned char>(text[i])) << (8 * (i % 4));
}

bool is_debug_info_set(const std::string& name) {
    return name.rfind("NonSemantic.Shader.DebugInfo", 0) == 0;
}

// glslang's names for the temporaries it makes to pass arguments: not the template's.
bool is_template_name(const std::string& name) {
    return !name.empty() && name != "param" && name.find('(') == std::string::npos && name[0] != '@';
}

// What the module says about names: the debug info set, its local variables, the OpName targets,
// and the module-scope values (constants, variables: named by SPIRV-Cross on its own terms).
struct DebugFacts {
    uint32_t debug_set = 0;
    std::map<uint32_t, std::string> strings;
    std::map<uint32_t, std::string> local_variables;  // DebugLocalVariable result -> name
    std::set<uint32_t> named;
    std::set<uint32_t> module_values;
};

bool is_module_value(uint16_t op) {
    switch (op) {
        case spv::OpConstant: case spv::OpConstantTrue: case spv::OpConstantFalse:
        case spv::OpConstantComposite: case spv::OpConstantNull: case spv::OpConstantSampler:
        case spv::OpSpecConstant: case spv::OpSpecConstantTrue: case spv::OpSpecConstantFalse:
        case spv::OpSpecConstantComposite: case spv::OpSpecConstantOp:
        case spv::OpVariable: case spv::OpUndef:
            return true;
        default:
            return false;
    }
}

DebugFacts gather(const SpirvBinary& words, const std::vector<Instruction>& list) {
    DebugFacts facts;
    bool in_function = false;
    for (const Instruction& in : list) {
        if (!in_function && is_module_value(in.opcode) && in.count >= 3) facts.module_values.insert(words[in.offset + 2]);
        const size_t a = in.offset;
        switch (in.opcode) {
            case spv::OpExtInstImport:
                if (in.count >= 3 && is_debug_info_set(spirv_literal_string(words, a + 2, a + in.count)))
                    facts.debug_set = words[a + 1];
                break;
            case spv::OpString:
                if (in.count >= 3) facts.strings[words[a + 1]] = spirv_literal_string(words, a + 2, a + in.count);
                break;
            case spv::OpName:
                if (in.count >= 2) facts.named.insert(words[a + 1]);
                break;
            case spv::OpFunction: in_function = true; break;
            case spv::OpFunctionEnd: in_function = false; break;
            case spv::OpExtInst:
                // OpExtInst type result set instruction operands...
                if (in.count >= 6 && facts.debug_set != 0 && words[a + 3] == facts.debug_set &&
                    words[a + 4] == NonSemanticShaderDebugInfo100DebugLocalVariable) {
                    auto name = facts.strings.find(words[a + 5]);
                    if (name != facts.strings.end()) facts.local_variables[words[a + 2]] = name->second;
                }
                break;
            default: break;
        }
    }
    return facts;
}

bool is_texture_read(uint16_t op) {
    switch (op) {
        case spv::OpImageSampleImplicitLod: case spv::OpImageSampleExplicitLod:
        case spv::OpImageSampleDrefImplicitLod: case spv::OpImageSampleDrefExplicitLod:
        case spv::OpImageFetch: case spv::OpImageGather:
            return true;
        default:
            return false;
    }
}

// The value -> name pairs the DebugValues give, in module order, the first name of a value winning.
std::map<uint32_t, std::string> value_names(const SpirvBinary& words, const std::vector<Instruction>& list,
                                            const DebugFacts& facts) {
    std::map<uint32_t, std::string> names;
    for (const Instruction& in : list) {
        const size_t a = in.offset;
        // DebugValue: local variable, value, expression; indexes when only part of the local is set.
        if (in.opcode != spv::OpExtInst || in.count != 8 || words[a + 3] != facts.debug_set ||
            words[a + 4] != NonSemanticShaderDebugInfo100DebugValue)
            continue;
        auto local = facts.local_variables.find(words[a + 5]);
        const uint32_t value = words[a + 6];
        if (local == facts.local_variables.end() || !is_template_name(local->second)) continue;
        if (facts.module_values.count(value) || facts.named.count(value)) continue;
        names.emplace(value, local->second);
    }
    // A texture read the template wrote inside an expression has no local, but it is the kind of
    // value SPIRV-Cross keeps in a temporary: call it what it is.
    for (const Instruction& in : list)
        if (in.count >= 3 && is_texture_read(in.opcode) && !facts.named.count(words[in.offset + 2]))
            names.emplace(words[in.offset + 2], "texel");
    return names;
}

// The module's sections before its OpNames (SPIR-V 2.4, logical layout).
bool precedes_names(uint16_t op) {
    switch (op) {
        case spv::OpCapability: case spv::OpExtension: case spv::OpExtInstImport: case spv::OpMemoryModel:
        case spv::OpEntryPoint: case spv::OpExecutionMode: case spv::OpExecutionModeId: case spv::OpString:
        case spv::OpSource: case spv::OpSourceContinued: case spv::OpSourceExtension:
            return true;
        default:
            return false;
    }
}

bool is_debug_instruction(const SpirvBinary& words, const Instruction& in, uint32_t debug_set) {
    const size_t a = in.offset;
    switch (in.opcode) {
        case spv::OpString:
        case spv::OpSource:
        case spv::OpSourceContinued:
        case spv::OpSourceExtension:
        case spv::OpModuleProcessed:
        case spv::OpLine:
        case spv::OpNoLine:
            return true;
        case spv::OpExtension:
            return spirv_literal_string(words, a + 1, a + in.count) == "SPV_KHR_non_semantic_info";
        case spv::OpExtInstImport:
            return debug_set != 0 && words[a + 1] == debug_set;
        case spv::OpExtInst:
            return debug_set != 0 && in.count >= 4 && words[a + 3] == debug_set;
        default:
            return false;
    }
}

}  // namespace

void name_values_and_strip_debug_info(SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords || words[0] != spv::MagicNumber) return;
    const auto parsed = detail::spirv_instructions(words);
    if (!parsed || parsed->empty()) return;
    const std::vector<Instruction>& list = *parsed;
    const DebugFacts facts = gather(words, list);
    const std::map<uint32_t, std::string> names = facts.debug_set ? value_names(words, list, facts)
                                                                  : std::map<uint32_t, std::string>{};

    SpirvBinary out(words.begin(), words.begin() + detail::kSpirvHeaderWords);
    out.reserve(words.size());
    bool names_written = names.empty();
    for (const Instruction& in : list) {
        // The new OpNames open the names section: before the first instruction past the strings.
        if (!names_written && !precedes_names(in.opcode)) {
            for (const auto& [id, name] : names) {
                const size_t first = out.size();
                out.push_back(0u);
                out.push_back(id);
                append_string(out, name);
                out[first] = (static_cast<uint32_t>(out.size() - first) << 16) | spv::OpName;
            }
            names_written = true;
        }
        if (is_debug_instruction(words, in, facts.debug_set)) continue;
        out.insert(out.end(), words.begin() + static_cast<std::ptrdiff_t>(in.offset),
                   words.begin() + static_cast<std::ptrdiff_t>(in.offset + in.count));
    }
    words = std::move(out);
}

}  // namespace crtforge
