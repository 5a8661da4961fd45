// glslang (in-process) -> SPIR-V -> SPIRV-Tools optimise + validate.
#include "generator/macro_budget.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "crtforge/parse_number.hpp"
#include "crtforge/version.hpp"
#include "crtforge/cache.hpp"
#include "crtforge/bounded_memo.hpp"
#include "generator/spirv_debug_names.hpp"
#include "generator/spirv_clamp_lowering.hpp"
#include "generator/spirv_pow_reduction.hpp"
#include "generator/spirv_spec_values.hpp"
#include "generator/spirv_words.hpp"

#include <mutex>
#include <optional>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>
#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/optimizer.hpp>

namespace crtforge {

const char* shader_stage_name(ShaderStage stage) {
    return stage == ShaderStage::Vertex ? "vert" : "frag";
}

namespace {

void ensure_glslang_initialized() {
    static std::once_flag once;
    std::call_once(once, [] { glslang::InitializeProcess(); });
}

EShLanguage to_glslang(ShaderStage stage) {
    return stage == ShaderStage::Vertex ? EShLangVertex : EShLangFragment;
}

// glslang logs look like "ERROR: templates/stages/x.glsl:12: 'foo' : undeclared identifier";
// without #line the file part is the string index ("0"). Turn the first error into a Diagnostic.
Diagnostic diagnostic_from_log(const std::string& log, const std::string& fallback_file,
                               const std::string& stage_label) {
    static const std::regex located(R"(^(?:ERROR|WARNING): (.+?):(\d+): (.*)$)");
    std::istringstream lines(log);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind("ERROR: ", 0) != 0) continue;
        std::smatch m;
        if (std::regex_match(line, m, located)) {
            std::string file = m[1].str();
            if (file == "0" || file.empty()) file = fallback_file;
            const auto line_number = parse_int(m[2].str());
            const int at = line_number && *line_number <= 1000000000 ? static_cast<int>(*line_number) : 0;
            return make_error(stage_label + ": " + m[3].str(), file, at);
        }
        return make_error(stage_label + ": " + line.substr(7), fallback_file);
    }
    return make_error(stage_label + ": compilation failed: " + log, fallback_file);
}

std::string join_messages(const std::vector<std::string>& messages) {
    std::string out;
    for (const auto& m : messages) out += (out.empty() ? "" : "; ") + m;
    return out;
}

// Parses (and for SPIR-V output, links) one shader. Returns the program for SPIR-V generation.
struct Parsed {
    std::unique_ptr<glslang::TShader> shader;
    std::unique_ptr<glslang::TProgram> program;
};

Result<std::shared_ptr<Parsed>> parse_shader(const std::string& source, ShaderStage stage,
                                             SourceLanguage language, bool vulkan, int version,
                                             bool es, const std::string& entry_point,
                                             const std::string& name) {
    if (auto bounded = detail::check_macro_expansion(source, name); !bounded.ok()) return bounded.error();
    ensure_glslang_initialized();
    auto parsed = std::make_shared<Parsed>();
    parsed->shader = std::make_unique<glslang::TShader>(to_glslang(stage));
    glslang::TShader& shader = *parsed->shader;
    const char* text = source.c_str();
    const char* names[] = {name.c_str()};
    shader.setStringsWithLengthsAndNames(&text, nullptr, names, 1);
    shader.setEntryPoint(entry_point.c_str());
    shader.setSourceEntryPoint(entry_point.c_str());
    auto messages = static_cast<EShMessages>(EShMsgDefault);
    if (vulkan) {
        shader.setEnvInput(language == SourceLanguage::Hlsl ? glslang::EShSourceHlsl : glslang::EShSourceGlsl,
                           to_glslang(stage), glslang::EShClientVulkan, 100);
        shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
        shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
        messages = static_cast<EShMessages>(messages | EShMsgSpvRules | EShMsgVulkanRules);
    }
    if (language == SourceLanguage::Hlsl) {
        messages = static_cast<EShMessages>(messages | EShMsgReadHlsl);
        // register(bN)/register(tN) become Vulkan bindings N, and the separate Texture2D +
        // SamplerState pair becomes one combined image sampler, as a D3D-style host binds them.
        shader.setHlslIoMapping(true);
        shader.setTextureSamplerTransformMode(EShTexSampTransUpgradeTextureRemoveSampler);
    }
    const std::string label = fmt::format("{} shader", shader_stage_name(stage));
    if (!shader.parse(GetDefaultResources(), version, es ? EEsProfile : ECoreProfile, false, false, messages))
        return diagnostic_from_log(shader.getInfoLog(), name, label);
    parsed->program = std::make_unique<glslang::TProgram>();
    parsed->program->addShader(&shader);
    if (!parsed->program->link(messages))
        return diagnostic_from_log(parsed->program->getInfoLog(), name, label + " (link)");
    if (language == SourceLanguage::Hlsl && !parsed->program->mapIO())
        return diagnostic_from_log(parsed->program->getInfoLog(), name, label + " (resource mapping)");
    return parsed;
}

// The validator's options without friendly names: naming every id of a module (for messages a
// valid module never prints) was most of a validation's time on the corpus's 50 K-word passes
// (perf: 7 % of a cold sweep). A module that fails is validated again with names, for the message.
spvtools::ValidatorOptions unnamed_validation() {
    spvtools::ValidatorOptions options;
    options.SetFriendlyNames(false);
    return options;
}

// Modules this process found valid, kept whole and compared word for word: the compiler checks
// each module it makes, and the Vulkan consumer checks the same bytes again as a host would (3.5-4.5 %
// of a cold corpus sweep ran spirv-val on modules it had already passed).
BoundedMemo<SpirvBinary>& valid_modules() {
    static BoundedMemo<SpirvBinary> memo(64u << 20, [](const SpirvBinary& m) { return m.size() * sizeof(uint32_t); });
    return memo;
}

}  // namespace

Status validate_spirv(const SpirvBinary& binary) {
    const std::string key = Cache::key({std::string_view(reinterpret_cast<const char*>(binary.data()), binary.size() * sizeof(uint32_t))});
    if (auto seen = valid_modules().find(key); seen && *seen == binary) return Ok{};
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    if (tools.Validate(binary.data(), binary.size(), unnamed_validation())) {
        valid_modules().put(key, binary);
        return Ok{};
    }
    std::vector<std::string> messages;
    tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t& pos, const char* msg) {
        messages.push_back(fmt::format("word {}: {}", pos.index, msg));
    });
    if (!tools.Validate(binary)) return make_validation_error("spirv-val: " + join_messages(messages));
    return Ok{};
}

std::string disassemble_spirv(const SpirvBinary& binary) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::string text;
    tools.Disassemble(binary, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES);
    return text;
}

namespace {

// SPIRV-Tools' performance passes; with `compact_ids`, then the ids renumbered in the order the
// module defines them.
Result<SpirvBinary> optimize_spirv(const SpirvBinary& module, const std::string& name, bool compact_ids = false) {
    spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_0);
    std::vector<std::string> messages;
    optimizer.SetMessageConsumer([&](spv_message_level_t level, const char*, const spv_position_t&, const char* msg) {
        if (level <= SPV_MSG_ERROR) messages.push_back(msg);
    });
    optimizer.RegisterPerformancePasses();
    if (compact_ids) optimizer.RegisterPass(spvtools::CreateCompactIdsPass());
    SpirvBinary optimized;
    spvtools::OptimizerOptions options;
    options.set_validator_options(unnamed_validation());
    if (!optimizer.Run(module.data(), module.size(), &optimized, options)) {
        // Its input invalid: say so with the ids named (the optimiser's own check names none).
        if (auto valid = validate_spirv(module); !valid.ok()) return make_validation_error(valid.error().message, name);
        return make_validation_error("spirv-opt failed: " + join_messages(messages), name);
    }
    return optimized;
}

// Whether a global variable is initialised by code (`vec2 s = uniformValue * 2.0;` at file scope):
// glslang runs that code at the start of main(), and its debug-info writer dereferences a null
// scope for it (Debian's glslang 15 crashes), so such a shader is compiled without debug info.
bool has_global_initialiser_code(const glslang::TIntermediate& intermediate) {
    const TIntermNode* root = intermediate.getTreeRoot();
    const glslang::TIntermAggregate* sequence = root ? const_cast<TIntermNode*>(root)->getAsAggregate() : nullptr;
    if (!sequence) return false;
    for (const TIntermNode* node : sequence->getSequence()) {
        const glslang::TIntermAggregate* aggregate = const_cast<TIntermNode*>(node)->getAsAggregate();
        const bool declaration = aggregate && (aggregate->getOp() == glslang::EOpFunction || aggregate->getOp() == glslang::EOpLinkerObjects);
        if (!declaration) return true;
    }
    return false;
}

// Optimised modules by what glslang made of their source without debug info: the instructions,
// types and names, none of the file names or line numbers a #line gives. Two sources that differ
// only there and in comments (the corpus imports each preset into a stage and folder of its own,
// and its presets share most passes) are optimised once. A module that fails is never kept, so
// each failure is reported with its own file names.
BoundedMemo<SpirvBinary>& optimized_memo() {
    static BoundedMemo<SpirvBinary> memo(256u << 20, [](const SpirvBinary& m) { return m.size() * sizeof(uint32_t); });
    return memo;
}

// `names`: the local names the optimised module will carry (carried_local_names), or "" when it
// carries none: two sources that differ only in a local's name make one plain module.
std::string optimized_memo_key(const SpirvBinary& plain, bool carry_names, const std::string& names) {
    const std::string_view words(reinterpret_cast<const char*>(plain.data()), plain.size() * sizeof(uint32_t));
    return Cache::key({"optimized", compiler_versions(), carry_names ? "names" : "plain", names, words});
}

// Where the source holds an array too long for one SPIR-V instruction: an initialised array's
// constant or constructor is one instruction of 3 + N words, and a word count is 16 bits. glslang
// does not check it and writes a word count of 0 (an invalid module spirv-val names only by word).
class OverlongArrayFinder : public glslang::TIntermTraverser {
public:
    static constexpr int kMaxElements = 65535 - 3;
    std::optional<glslang::TSourceLoc> found;

    void visitConstantUnion(glslang::TIntermConstantUnion* node) override { check(*node); }
    // A const array's value is its symbol's (and the finder runs only on a module already too long,
    // so an array this long is the likely cause even where glslang keeps no value with it).
    void visitSymbol(glslang::TIntermSymbol* node) override { check(*node); }
    bool visitAggregate(glslang::TVisit, glslang::TIntermAggregate* node) override {
        if (node->getSequence().size() > static_cast<size_t>(kMaxElements) && !found) found = node->getLoc();
        return !found;
    }

private:
    void check(const glslang::TIntermTyped& node) {
        if (!found && node.getType().isArray() && node.getType().getOuterArraySize() > kMaxElements) found = node.getLoc();
    }
};

// The source line declaring an array longer than `limit` (`[N]`), through the #line directives the
// generator writes: glslang keeps no tree node of a global constant nothing reads.
std::optional<std::pair<std::string, int>> overlong_array_line(const std::string& source, const std::string& name, long limit) {
    static const std::regex directive(R"re(^\s*#\s*line\s+(\d+)(?:\s+"([^"]*)")?)re"),
        size(R"re(\[\s*(\d{1,12})\s*\])re");
    std::istringstream lines(source);
    std::string line, file = name;
    long number = 1;
    for (; std::getline(lines, line); ++number) {
        std::smatch m;
        if (std::regex_search(line, m, directive)) {
            number = std::stol(m[1].str()) - 1;  // the next line is number m[1]
            if (m[2].matched) file = m[2].str();
            continue;
        }
        for (auto it = std::sregex_iterator(line.begin(), line.end(), size); it != std::sregex_iterator(); ++it)
            if (std::stoll((*it)[1].str()) > limit) return std::make_pair(file, static_cast<int>(std::min<long>(number, 1000000000)));
    }
    return std::nullopt;
}

Diagnostic overlong_instruction_error(const glslang::TIntermediate& intermediate, const std::string& source, const std::string& name) {
    const std::string message = fmt::format(
        "an array or initialiser list of more than {} elements: SPIR-V holds one in a single instruction of at most 65535 words",
        OverlongArrayFinder::kMaxElements);
    OverlongArrayFinder finder;
    if (TIntermNode* root = intermediate.getTreeRoot()) root->traverse(&finder);
    if (finder.found && finder.found->name) return make_error(message, finder.found->name->c_str(), finder.found->line);
    if (auto at = overlong_array_line(source, name, OverlongArrayFinder::kMaxElements)) return make_error(message, at->first, at->second);
    return make_error(message, name, finder.found ? finder.found->line : 0);
}

}  // namespace

Result<SpirvBinary> compile_to_spirv(const std::string& source, const CompileOptions& options) {
    const std::string name = options.source_name.empty() ? std::string("<source>") : options.source_name;
    auto parsed = parse_shader(source, options.stage, options.language, true,
                               options.language == SourceLanguage::Hlsl ? 100 : 450, false,
                               options.entry_point, name);
    if (!parsed.ok()) return parsed.error();

    SpirvBinary spirv;
    spv::SpvBuildLogger logger;
    glslang::SpvOptions spv_options;
    spv_options.disableOptimizer = true;  // SPIRV-Tools does it below, with our pass list
    const glslang::TIntermediate& intermediate = *parsed.value()->program->getIntermediate(to_glslang(options.stage));
    const bool debug_info_safe = !has_global_initialiser_code(intermediate);
    spv_options.generateDebugInfo = options.debug_lines && debug_info_safe;
    // Readable output: the template's local names ride through the optimiser as NonSemantic debug
    // info and become OpNames of the SSA values afterwards (spirv_debug_names.cpp).
    const bool carry_names = options.local_names && options.optimize && !options.debug_lines &&
                             options.language == SourceLanguage::Glsl && debug_info_safe;
    if (carry_names) {
        spv_options.generateDebugInfo = true;
        spv_options.emitNonSemanticShaderDebugInfo = true;
    }
    glslang::GlslangToSpv(intermediate, spirv, &logger, &spv_options);
    if (spirv.empty()) return make_error("glslang produced no SPIR-V: " + logger.getAllMessages(), name);
    if (!detail::spirv_instructions(spirv)) return overlong_instruction_error(intermediate, source, name);

    // The memo's key is the module without debug info (OpLine output, debug_lines, names its files:
    // it is not memoised) and the local names it will carry, its specialization constants
    // (BakedParams::Specialized) cleared: it is optimised with them cleared, so presets that differ
    // only in those values share one optimisation, and each gets its values back after.
    std::string memo_key;
    std::map<uint32_t, SpecValue> spec_values;
    std::optional<BoundedMemo<SpirvBinary>::Claim> claim;
    if (options.optimize && !options.debug_lines) {
        SpirvBinary plain;
        if (spv_options.generateDebugInfo) {
            glslang::SpvOptions plain_options = spv_options;
            plain_options.generateDebugInfo = false;
            plain_options.emitNonSemanticShaderDebugInfo = false;
            spv::SpvBuildLogger plain_logger;
            glslang::GlslangToSpv(intermediate, plain, &plain_logger, &plain_options);
        }
        SpirvBinary& keyed = spv_options.generateDebugInfo ? plain : spirv;
        spec_values = spec_constant_values(keyed);
        if (!spec_values.empty()) {
            clear_spec_constant_values(spirv);
            if (&keyed != &spirv) clear_spec_constant_values(keyed);
        }
        memo_key = optimized_memo_key(keyed, carry_names, carry_names ? carried_local_names(spirv) : std::string());
        auto known = optimized_memo().find(memo_key);
        if (!known) {  // a worker optimising the same module: wait for it, then look again
            claim.emplace(optimized_memo(), memo_key);
            known = optimized_memo().find(memo_key);
        }
        if (known) {
            write_spec_constant_values(*known, spec_values);
            return std::move(*known);
        }
    }

    if (options.optimize) {
        lower_clamps(spirv);  // first: spirv-opt folds clamp by a rule that holds only when lo <= hi
        if (auto optimized = optimize_spirv(spirv, name); optimized.ok()) spirv = std::move(optimized.value());
        else return optimized.error();
        if (carry_names) {
            // The debug info holds back some of the optimiser's work (an emptied branch stays while
            // its debug scope does, a value a DebugValue reads stays alive): optimising the named,
            // stripped module again gives the module an optimisation without names gives. (A cleanup
            // list alone — ADCE, CFG cleanup, block merge, dead constants — left a dead store in
            // one WGSL snapshot shader: the whole performance list it is.) The ids are compacted
            // after: the debug info (its file names, its line records) took ids of its own, and the
            // module must not depend on them, or on which source of the same code came first.
            name_values_and_strip_debug_info(spirv);
            if (auto optimized = optimize_spirv(spirv, name, true); optimized.ok()) spirv = std::move(optimized.value());
            else return optimized.error();
        }
        reduce_constant_powers(spirv);  // last: the exponents are constants only once spirv-opt has folded
        if (carry_names) name_unnamed_values(spirv);
    }
    if (auto valid = validate_spirv(spirv); !valid.ok())
        return make_validation_error(valid.error().message + " (the generator produced invalid SPIR-V)", name);
    if (!memo_key.empty()) optimized_memo().put(memo_key, spirv);
    write_spec_constant_values(spirv, spec_values);
    return spirv;
}

Status check_glsl(const std::string& source, ShaderStage stage, int version, bool es) {
    auto parsed = parse_shader(source, stage, SourceLanguage::Glsl, false, version, es, "main",
                               fmt::format("<glsl {}{}>", version, es ? " es" : ""));
    if (!parsed.ok()) return parsed.error();
    return Ok{};
}

Status check_hlsl(const std::string& source, ShaderStage stage, const std::string& entry_point) {
    CompileOptions options;
    options.stage = stage;
    options.language = SourceLanguage::Hlsl;
    options.optimize = false;
    options.entry_point = entry_point;
    options.source_name = "<hlsl>";
    auto spirv = compile_to_spirv(source, options);
    if (!spirv.ok()) return spirv.error();
    return Ok{};
}

std::string compiler_versions() {
    return fmt::format("crtforge {}; glslang {}.{}.{}; {}", CRTFORGE_VERSION, GLSLANG_VERSION_MAJOR,
                       GLSLANG_VERSION_MINOR, GLSLANG_VERSION_PATCH, spvSoftwareVersionString());
}

Result<std::string> preprocess_vulkan_glsl(const std::string& source, ShaderStage stage, const std::string& name) {
    if (auto bounded = detail::check_macro_expansion(source, name); !bounded.ok()) return bounded.error();
    ensure_glslang_initialized();
    glslang::TShader shader(to_glslang(stage));
    const char* text = source.c_str();
    const char* names[] = {name.c_str()};
    shader.setStringsWithLengthsAndNames(&text, nullptr, names, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, to_glslang(stage), glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
    const auto messages = static_cast<EShMessages>(EShMsgDefault | EShMsgSpvRules | EShMsgVulkanRules);
    glslang::TShader::ForbidIncluder no_includes;
    std::string out;
    if (!shader.preprocess(GetDefaultResources(), 450, ENoProfile, false, false, messages, &out, no_includes))
        return diagnostic_from_log(shader.getInfoLog(), name, fmt::format("{} shader (preprocessor)", shader_stage_name(stage)));
    return out;
}

}  // namespace crtforge
