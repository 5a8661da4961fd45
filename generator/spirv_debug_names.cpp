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

#include <glslang/SPIRV/GLSL.std.450.h>
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
    std::map<uint32_t, std::string> name_of;          // OpName target -> its name
    std::set<uint32_t> module_values;
    std::map<uint32_t, uint32_t> vector_sizes;        // OpTypeVector result -> component count
    std::set<uint32_t> bool_types;                    // OpTypeBool, and vectors of it
    std::map<uint32_t, uint32_t> value_types;         // a function's value -> its type (first definition)
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
        bool has_result = false, has_type = false;
        spv::HasResultAndType(static_cast<spv::Op>(in.opcode), &has_result, &has_type);
        if (in_function && has_result && has_type && in.count >= 3) facts.value_types.emplace(words[a + 2], words[a + 1]);
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
                if (in.count >= 3) facts.name_of[words[a + 1]] = spirv_literal_string(words, a + 2, a + in.count);
                break;
            case spv::OpTypeVector:
                if (in.count == 4) facts.vector_sizes[words[a + 1]] = words[a + 3];
                if (in.count == 4 && facts.bool_types.count(words[a + 2])) facts.bool_types.insert(words[a + 1]);
                break;
            case spv::OpTypeBool:
                if (in.count == 2) facts.bool_types.insert(words[a + 1]);
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

bool is_condition(uint16_t op) {
    switch (op) {
        case spv::OpFOrdLessThan: case spv::OpFOrdGreaterThan: case spv::OpFOrdLessThanEqual: case spv::OpFOrdGreaterThanEqual:
        case spv::OpFOrdEqual: case spv::OpFOrdNotEqual: case spv::OpFUnordLessThan: case spv::OpFUnordGreaterThan:
        case spv::OpFUnordLessThanEqual: case spv::OpFUnordGreaterThanEqual: case spv::OpFUnordEqual: case spv::OpFUnordNotEqual:
        case spv::OpSLessThan: case spv::OpSGreaterThan: case spv::OpSLessThanEqual: case spv::OpSGreaterThanEqual:
        case spv::OpULessThan: case spv::OpUGreaterThan: case spv::OpULessThanEqual: case spv::OpUGreaterThanEqual:
        case spv::OpIEqual: case spv::OpINotEqual: case spv::OpLogicalAnd: case spv::OpLogicalOr: case spv::OpLogicalNot:
        case spv::OpLogicalEqual: case spv::OpLogicalNotEqual: case spv::OpIsNan: case spv::OpIsInf: case spv::OpAny: case spv::OpAll:
            return true;
        default:
            return false;
    }
}

// A component or swizzle of a named vector, which SPIRV-Cross keeps in a temporary of its own
// (`float _1294 = sampleUv.x;`), is named after it: sampleUv_x, q_zw. In module order, so a
// swizzle of a swizzle builds on its base's name.
void add_component_names(const SpirvBinary& words, const std::vector<Instruction>& list, const DebugFacts& facts,
                         std::map<uint32_t, std::string>& names) {
    auto base_name = [&](uint32_t id) -> std::string {
        if (auto n = names.find(id); n != names.end()) return n->second;
        if (auto n = facts.name_of.find(id); n != facts.name_of.end()) return n->second;
        return {};
    };
    auto vector_size = [&](uint32_t id) -> uint32_t {
        auto type = facts.value_types.find(id);
        if (type == facts.value_types.end()) return 0;
        auto size = facts.vector_sizes.find(type->second);
        return size == facts.vector_sizes.end() ? 0 : size->second;
    };
    static constexpr const char* kLetters = "xyzw";
    for (const Instruction& in : list) {
        const size_t a = in.offset;
        if (in.count < 5 || (in.opcode != spv::OpCompositeExtract && in.opcode != spv::OpVectorShuffle)) continue;
        const uint32_t id = words[a + 2], vector = words[a + 3];
        if (facts.named.count(id) || names.count(id) || facts.module_values.count(id)) continue;
        const std::string base = base_name(vector);
        const uint32_t size = vector_size(vector);
        // A name ending in '_' would make a "__" (reserved in GLSL).
        if (base.empty() || base.back() == '_' || size == 0) continue;
        std::string letters;
        if (in.opcode == spv::OpCompositeExtract) {
            if (in.count == 5 && words[a + 4] < size) letters = kLetters[words[a + 4]];
        } else if (in.count >= 6 && in.count <= 9) {  // a shuffle of the first vector's components only
            for (size_t k = a + 5; k < a + in.count; ++k) {
                if (words[k] >= size) {
                    letters.clear();
                    break;
                }
                letters += kLetters[words[k]];
            }
        }
        if (!letters.empty()) names.emplace(id, base + "_" + letters);
    }
    // A condition SPIRV-Cross keeps in a temporary (a short-circuit's operands, a select's test) is
    // one: `bool inside_1 = ...` reads better than `bool _1762`; SPIRV-Cross numbers repeats.
    for (const Instruction& in : list) {
        const bool bool_phi = in.opcode == spv::OpPhi && in.count >= 3 && facts.bool_types.count(words[in.offset + 1]);
        if (in.count < 3 || !(is_condition(in.opcode) || bool_phi)) continue;
        const uint32_t id = words[in.offset + 2];
        if (!facts.named.count(id) && !facts.module_values.count(id)) names.emplace(id, "cond");
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
    add_component_names(words, list, facts, names);
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

// An OpName for each (id, name), appended to `out`.
void append_names(SpirvBinary& out, const std::map<uint32_t, std::string>& names) {
    for (const auto& [id, name] : names) {
        const size_t first = out.size();
        out.push_back(0u);
        out.push_back(id);
        append_string(out, name);
        out[first] = (static_cast<uint32_t>(out.size() - first) << 16) | spv::OpName;
    }
}

// `words` with `names` as new OpNames opening the names section (before the first instruction
// past the strings) and without the instructions `drop` picks; untouched when neither applies.
template <typename Drop>
void rewrite_names(SpirvBinary& words, const std::vector<Instruction>& list, const std::map<uint32_t, std::string>& names,
                   Drop&& drop) {
    bool names_written = names.empty();
    detail::rewrite_instructions(words, list, [&](const Instruction& in, SpirvBinary& out, uint32_t&) {
        const bool open_names = !names_written && !precedes_names(in.opcode);
        const bool dropped = drop(in);
        if (!open_names && !dropped) return false;
        if (open_names) {
            append_names(out, names);
            names_written = true;
        }
        if (!dropped) detail::append_copy(out, words, in);
        return true;
    });
}

// The id `in` defines (after its result type where it has one), or 0; with `values_only`, 0 too
// where it has no result type (a type, a label).
uint32_t result_id(const SpirvBinary& words, const Instruction& in, bool values_only = false) {
    bool has_result = false, has_type = false;
    spv::HasResultAndType(static_cast<spv::Op>(in.opcode), &has_result, &has_type);
    const size_t at = in.offset + (has_type ? 2 : 1);
    return has_result && (has_type || !values_only) && at < in.offset + in.count ? words[at] : 0;
}

// What a value with no template name is, as a name. None is a function of GLSL, HLSL or WGSL
// (a local named `length` would hide the function); a reserved one gets its `_` downstream.
const char* kind_name(const SpirvBinary& words, const Instruction& in, uint32_t glsl_set) {
    switch (in.opcode) {
        case spv::OpFMul: case spv::OpIMul: case spv::OpVectorTimesScalar: case spv::OpMatrixTimesScalar:
        case spv::OpVectorTimesMatrix: case spv::OpMatrixTimesVector: case spv::OpMatrixTimesMatrix:
            return "product";
        case spv::OpFAdd: case spv::OpIAdd: return "sum";
        case spv::OpFSub: case spv::OpISub: return "difference";
        case spv::OpFDiv: case spv::OpSDiv: case spv::OpUDiv: return "quotient";
        case spv::OpFMod: case spv::OpFRem: case spv::OpSMod: case spv::OpSRem: case spv::OpUMod: return "remainder";
        case spv::OpFNegate: case spv::OpSNegate: return "negated";
        case spv::OpDot: return "dot_product";
        case spv::OpSelect: return "chosen";
        case spv::OpPhi: return "merged";
        case spv::OpCompositeConstruct: return "composite";
        case spv::OpCompositeExtract: case spv::OpVectorShuffle: return "part";
        case spv::OpCompositeInsert: return "updated";
        case spv::OpConvertFToS: case spv::OpConvertFToU: case spv::OpConvertSToF: case spv::OpConvertUToF:
        case spv::OpUConvert: case spv::OpSConvert: case spv::OpFConvert: case spv::OpBitcast:
            return "converted";
        case spv::OpLoad: return "loaded";
        case spv::OpUndef: return "undefined";
        case spv::OpFunctionParameter: return "argument";
        case spv::OpVariable: return "local";
        case spv::OpImageQuerySize: case spv::OpImageQuerySizeLod: return "texture_size";
        case spv::OpExtInst:
            if (in.count < 5 || words[in.offset + 3] != glsl_set) break;
            switch (words[in.offset + 4]) {
                case GLSLstd450FClamp: case GLSLstd450SClamp: case GLSLstd450UClamp: case GLSLstd450NClamp: return "clamped";
                case GLSLstd450FMix: return "blend";
                case GLSLstd450Pow: return "power";
                case GLSLstd450Exp: case GLSLstd450Exp2: return "exponential";
                case GLSLstd450Log: case GLSLstd450Log2: return "logarithm";
                case GLSLstd450Sqrt: return "root";
                case GLSLstd450InverseSqrt: return "inverse_root";
                case GLSLstd450Floor: return "floored";
                case GLSLstd450Fract: return "fraction";
                case GLSLstd450Sin: return "sine";
                case GLSLstd450Cos: return "cosine";
                case GLSLstd450FAbs: case GLSLstd450SAbs: return "magnitude";
                case GLSLstd450FMin: case GLSLstd450SMin: case GLSLstd450UMin: case GLSLstd450NMin: return "smaller";
                case GLSLstd450FMax: case GLSLstd450SMax: case GLSLstd450UMax: case GLSLstd450NMax: return "larger";
                case GLSLstd450Length: return "magnitude";
                case GLSLstd450Normalize: return "direction";
                case GLSLstd450SmoothStep: return "smoothed";
                default: break;
            }
            break;
        default:
            break;
    }
    return "value";
}

}  // namespace

void drop_annotations_of_missing_ids(SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords || words[0] != spv::MagicNumber) return;
    const auto parsed = detail::spirv_instructions(words);
    if (!parsed) return;
    std::set<uint32_t> defined;
    for (const Instruction& in : *parsed)
        if (const uint32_t id = result_id(words, in)) defined.insert(id);
    rewrite_names(words, *parsed, {}, [&](const Instruction& in) {
        const bool annotation = in.opcode == spv::OpName || in.opcode == spv::OpMemberName || in.opcode == spv::OpDecorate ||
                                in.opcode == spv::OpMemberDecorate;
        return annotation && in.count >= 3 && !defined.count(words[in.offset + 1]);
    });
}

void name_unnamed_values(SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords || words[0] != spv::MagicNumber) return;
    const auto parsed = detail::spirv_instructions(words);
    if (!parsed || parsed->empty()) return;
    const std::vector<Instruction>& list = *parsed;
    std::set<uint32_t> named;
    uint32_t glsl_set = 0;
    for (const Instruction& in : list) {
        if (in.opcode == spv::OpName && in.count >= 3) named.insert(words[in.offset + 1]);
        if (in.opcode == spv::OpExtInstImport && in.count >= 3 &&
            spirv_literal_string(words, in.offset + 2, in.offset + in.count) == "GLSL.std.450")
            glsl_set = words[in.offset + 1];
    }
    // Values inside functions (not a function's own id), and the undefined values SPIRV-Cross
    // declares as globals: those get a number each from the second on (two globals of one name,
    // a vec3 and a float `undefined`, do not compile), where local names are made unique per
    // function by SPIRV-Cross.
    std::map<uint32_t, std::string> names;
    bool in_function = false;
    int undefined = 0;
    for (const Instruction& in : list) {
        if (in.opcode == spv::OpFunction) in_function = true;
        if (in.opcode == spv::OpFunctionEnd) in_function = false;
        if ((!in_function && in.opcode != spv::OpUndef) || in.opcode == spv::OpFunction) continue;
        const uint32_t id = result_id(words, in, /*values_only*/ true);
        if (!id || named.count(id)) continue;
        std::string name = kind_name(words, in, glsl_set);
        if (in.opcode == spv::OpUndef && ++undefined > 1) name += std::to_string(undefined);
        names.emplace(id, std::move(name));
    }
    rewrite_names(words, list, names, [](const Instruction&) { return false; });
}

std::string carried_local_names(const SpirvBinary& words) {
    const auto list = detail::spirv_instructions(words);
    if (!list) return {};
    std::string out;
    for (const auto& [id, name] : gather(words, *list).local_variables) out.append(name).push_back('\n');
    return out;
}

void name_values_and_strip_debug_info(SpirvBinary& words) {
    if (words.size() < detail::kSpirvHeaderWords || words[0] != spv::MagicNumber) return;
    const auto parsed = detail::spirv_instructions(words);
    if (!parsed || parsed->empty()) return;
    const std::vector<Instruction>& list = *parsed;
    const DebugFacts facts = gather(words, list);
    const std::map<uint32_t, std::string> names = facts.debug_set ? value_names(words, list, facts)
                                                                  : std::map<uint32_t, std::string>{};
    rewrite_names(words, list, names, [&](const Instruction& in) { return is_debug_instruction(words, in, facts.debug_set); });
}

}  // namespace crtforge
