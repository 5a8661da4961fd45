// Exported shaders keep the template's local names (generator/spirv_debug_names.cpp): the names ride
// through spirv-opt as debug info, become OpNames, and change no instruction of the module.
#include <algorithm>
#include <regex>
#include <set>
#include <sstream>

#include <catch2/catch.hpp>

#include <spirv-tools/libspirv.hpp>

#include "crtforge/assembler.hpp"
#include "crtforge/validate/target_render.hpp"
#include "generator/spirv_debug_names.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

std::string fragment_text(const CompiledVariant& c, TargetId target) {
    auto out = emit_target(c, target, Cache());
    REQUIRE(out.ok());
    for (const OutputFile& f : out.value().files)
        if (f.is_shader() && f.stage == ShaderStage::Fragment) return f.data;
    return out.value().files.back().data;  // WGSL: one file, both stages
}

// A module's instructions with every id written as %, names and debug info left out, sorted: the
// optimiser may order types, constants and a few loads differently (scheduling, not instructions).
struct Shape {
    std::vector<std::string> module_lines, function_lines;
    bool operator==(const Shape&) const = default;
};

Shape shape_of(const SpirvBinary& module) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    std::string text;
    REQUIRE(tools.Disassemble(module, &text, SPV_BINARY_TO_TEXT_OPTION_NO_HEADER));
    static const std::regex id(R"(%\w+)");
    static const std::regex debug(R"(\b(OpName|OpMemberName|OpSource\w*|OpString|OpLine|OpNoLine|OpModuleProcessed)\b)");
    Shape shape;
    bool in_function = false;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        if (std::regex_search(line, debug)) continue;
        line = std::regex_replace(line, id, "%");
        line.erase(0, line.find_first_not_of(' '));
        in_function = in_function || line.find("OpFunction ") != std::string::npos;
        (in_function ? shape.function_lines : shape.module_lines).push_back(line);
    }
    std::sort(shape.module_lines.begin(), shape.module_lines.end());
    std::sort(shape.function_lines.begin(), shape.function_lines.end());
    return shape;
}

// Counts the declarations of a GLSL-like text whose name is a SPIR-V id (`vec2 _342`) and those
// with a template name.
std::pair<int, int> numbered_and_named(const std::string& glsl) {
    static const std::regex decl(R"(\n\s+(?:float|int|uint|bool|[biu]?vec[234]|mat[234]) (\w+)( =|;))");
    int numbered = 0, named = 0;
    for (auto it = std::sregex_iterator(glsl.begin(), glsl.end(), decl); it != std::sregex_iterator(); ++it)
        ((*it)[1].str()[0] == '_' ? numbered : named)++;
    return {numbered, named};
}

}  // namespace

TEST_CASE("exported shaders keep the template's local names on every target", "[targets][readable]") {
    const TemplateLibrary& lib = test::shipped_library();
    const CompiledVariant classic = test::compile_or_fail(lib, "classic");
    // curvature_atari's uv and r2, main's sampleUv, aberration's offset, the texture reads.
    const std::string glsl = fragment_text(classic, TargetId::Glsl330);
    CHECK_THAT(glsl, Catch::Contains("vec2 uv = (vTexCoord * 2.0) - vec2(1.0);"));
    CHECK_THAT(glsl, Catch::Contains("float r2 = dot(uv, uv);"));
    CHECK_THAT(glsl, Catch::Contains("vec2 sampleUv = "));
    CHECK_THAT(glsl, Catch::Contains("vec2 offset = vec2(crt.rgbOffset, 0.0);"));
    CHECK_THAT(glsl, Catch::Contains("vec4 texel = texture(source, sampleUv);"));
    CHECK_THAT(fragment_text(classic, TargetId::Hlsl50), Catch::Contains("float2 sampleUv = "));
    CHECK_THAT(fragment_text(classic, TargetId::Wgsl), Catch::Contains("let sampleUv = "));
    CHECK_THAT(fragment_text(classic, TargetId::Godot3), Catch::Contains("vec2 sampleUv = "));
    CHECK_THAT(fragment_text(classic, TargetId::Godot4), Catch::Contains("float r2 = dot(uv, uv);"));

    // Over every pass of every preset, every declaration carries a name: the template's, or (a value
    // the template wrote inside an expression) what it is; no target's text has an SSA number.
    const std::regex ssa_number(R"(\b_[0-9]+\b)");
    int numbered = 0, named = 0;
    for (const Preset& p : lib.presets()) {
        auto scene = compile_scene(lib, p, VariantOptions{}, Cache());
        REQUIRE(scene.ok());
        for (const CompiledVariant& pass : scene.value()) {
            const auto [n, t] = numbered_and_named(fragment_text(pass, TargetId::Glsl450));
            numbered += n;
            named += t;
            for (TargetId target : {TargetId::Glsl330, TargetId::GlslEs300, TargetId::Hlsl60, TargetId::Wgsl, TargetId::Godot4,
                                    TargetId::Godot3}) {
                const std::string text = fragment_text(pass, target);
                std::smatch found;
                const bool numbered_name = std::regex_search(text, found, ssa_number);
                INFO(p.name << " " << target_info(target).name << ": " << (numbered_name ? found.str() : std::string()));
                CHECK_FALSE(numbered_name);
            }
        }
    }
    INFO(named << " named declarations, " << numbered << " numbered");
    CHECK(numbered == 0);
    CHECK(named > 0);
}

TEST_CASE("a component or swizzle of a named vector, and a condition, are named in exported code", "[targets][readable]") {
    const TemplateLibrary& lib = test::shipped_library();
    // A temporary that only holds part of a named value, or a condition, never keeps its SSA number.
    const std::regex component(R"((?:float|vec[234]) _[0-9]+ = [A-Za-z]\w*\.[xyzw]{1,4};)");
    const std::regex condition(R"(\b(?:bool|bvec[234]) _[0-9]+\b)");
    int conditions = 0;
    for (const Preset& p : lib.presets()) {
        auto scene = compile_scene(lib, p, VariantOptions{}, Cache());
        REQUIRE(scene.ok());
        for (const CompiledVariant& pass : scene.value())
            for (TargetId target : {TargetId::Glsl330, TargetId::Glsl450, TargetId::Godot4}) {
                const std::string text = fragment_text(pass, target);
                INFO(p.name << " " << target_info(target).name);
                CHECK_FALSE(std::regex_search(text, component));
                CHECK_FALSE(std::regex_search(text, condition));
                conditions += text.find("cond") != std::string::npos;
            }
    }
    CHECK(conditions > 0);  // conditions were kept in temporaries, and named
}

TEST_CASE("carrying the names adds or removes no instruction and leaves no debug info", "[targets][readable]") {
    const TemplateLibrary& lib = test::shipped_library();
    size_t modules = 0;
    for (const Preset& p : lib.presets())
        for (size_t pass = 0; pass < p.passes.size(); ++pass) {
            auto variant = make_variant(lib, p, VariantOptions{}, pass);
            REQUIRE(variant.ok());
            const AssembledShader source = assemble(lib, variant.value());
            CompileOptions with, without;
            without.local_names = false;
            auto named = compile_to_spirv(source.fragment, with);
            auto plain = compile_to_spirv(source.fragment, without);
            REQUIRE(named.ok());
            REQUIRE(plain.ok());
            INFO(p.name << " pass " << pass);
            CHECK(shape_of(named.value()) == shape_of(plain.value()));
            const std::string text = disassemble_spirv(named.value());
            CHECK(text.find("NonSemantic") == std::string::npos);
            CHECK(text.find("OpLine") == std::string::npos);
            CHECK(text.find("OpString") == std::string::npos);
            ++modules;
        }
    CHECK(modules > 20);
}

TEST_CASE("a template local named like a word of a target language or a param is renamed", "[targets][readable]") {
    // Legal GLSL locals that are Godot's (light, TIME), HLSL's (point, line) and WGSL's (loop) words,
    // and one named like a param of another stage.
    test::ScratchTemplates templates;
    templates.write("stages/user_words.toml", R"(name = "user_words"
doc = "Locals named like other languages' words"
order = 27

[[param]]
name = "wordsGain"
type = "float"
range = [0.0, 2.0]
default = 0.5
doc = "Gain"
runtime = true

[[form]]
name = "words"
doc = "Arithmetic on locals with awkward names"
params = ["wordsGain"]
color = "user_words"
)");
    templates.write("stages/user_words.glsl", R"(vec3 user_words(vec3 color, CrtFrag frag) {
    float point = dot(color, vec3(0.25)) * wordsGain;
    float line = point * point + frag.uv.y;
    float loop = sin(line) * line + point;
    float TIME = loop * point + line * loop;
    float scanlineIntensity = TIME * 0.5 + point;  // the scanlines stage's param, which runs after this
    vec3 light = color * TIME * scanlineIntensity + vec3(point, line, loop) * scanlineIntensity;
    return light * light * TIME + color * 0.5;
}
)");
    templates.write("presets/words.toml", "name = \"words\"\ndoc = \"awkward names\"\n\n[stages.user_words]\nwordsGain = 0.7\n\n[stages.scanlines]\nscanlineIntensity = 0.3\n");
    auto loaded = templates.load();
    REQUIRE(loaded.ok());
    const CompiledVariant c = test::compile_or_fail(*loaded.value(), "words");
    for (TargetId t : {TargetId::Glsl330, TargetId::GlslEs300, TargetId::Hlsl50, TargetId::Wgsl, TargetId::Godot3, TargetId::Godot4}) {
        auto out = emit_target(c, t, Cache());
        REQUIRE(out.ok());
        for (const OutputFile& f : out.value().files) {
            INFO(target_info(t).name << ":\n" << f.data);
            if (f.is_shader()) CHECK(consume_output(t, f).ok());
        }
    }
    const std::string godot = fragment_text(c, TargetId::Godot3);
    CHECK_THAT(godot, Catch::Contains("vec3 light_ = "));
    CHECK_THAT(godot, Catch::Contains("float TIME_ = "));
    CHECK_THAT(godot, !Catch::Contains(" TIME = "));
    // The local named like the scanlines' param does not hide the uniform Godot declares for it.
    CHECK_THAT(godot, Catch::Contains("uniform float scanlineIntensity"));
    CHECK_THAT(godot, Catch::Contains("float scanlineIntensity_ = "));
}

// SPIRV-Cross declares every undefined value as a global of its own: two named alike (a vec3 and
// a float `undefined`) did not compile on GLSL or HLSL (crt-guest-advanced's PrePass).
TEST_CASE("undefined values get a name each, none twice", "[targets][readable]") {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_0);
    SpirvBinary module;
    REQUIRE(tools.Assemble(R"(
               OpCapability Shader
               OpMemoryModel Logical GLSL450
               OpEntryPoint Fragment %main "main"
               OpExecutionMode %main OriginUpperLeft
       %void = OpTypeVoid
         %fn = OpTypeFunction %void
      %float = OpTypeFloat 32
    %v3float = OpTypeVector %float 3
         %u1 = OpUndef %v3float
         %u2 = OpUndef %float
         %u3 = OpUndef %float
       %main = OpFunction %void None %fn
      %entry = OpLabel
               OpReturn
               OpFunctionEnd
)", &module));
    name_unnamed_values(module);
    std::string text;
    REQUIRE(tools.Disassemble(module, &text, SPV_BINARY_TO_TEXT_OPTION_NO_HEADER));
    std::set<std::string> names;
    static const std::regex name(R"re(OpName %\w+ "(\w+)")re");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), name); it != std::sregex_iterator(); ++it) names.insert((*it)[1].str());
    CHECK(names == std::set<std::string>{"undefined", "undefined2", "undefined3"});
}
