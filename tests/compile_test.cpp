// GLSL 450 assembly -> SPIR-V: every preset compiles and validates; template errors point at the
// template file and line.
#include <catch2/catch.hpp>

#include <glslang/SPIRV/spirv.hpp>

#include "generator/spirv_words.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

TEST_CASE("every preset compiles to SPIR-V that passes spirv-val, in both precisions", "[compile]") {
    const TemplateLibrary& lib = test::shipped_library();
    for (const Preset& p : lib.presets()) {
        for (Precision precision : {Precision::High, Precision::Medium}) {
            INFO(p.name << " precision " << precision_name(precision));
            VariantOptions options;
            options.precision = precision;
            CompiledVariant c = test::compile_or_fail(lib, p.name, options);
            CHECK(validate_spirv(c.fragment).ok());
            CHECK(validate_spirv(c.vertex).ok());
        }
    }
}

TEST_CASE("medium precision marks the module RelaxedPrecision", "[compile]") {
    const TemplateLibrary& lib = test::shipped_library();
    VariantOptions medium;
    medium.precision = Precision::Medium;
    CHECK_THAT(disassemble_spirv(test::compile_or_fail(lib, "classic", medium).fragment), Catch::Contains("RelaxedPrecision"));
    CHECK_THAT(disassemble_spirv(test::compile_or_fail(lib, "classic").fragment), !Catch::Contains("RelaxedPrecision"));
}

TEST_CASE("baking folds constants: fewer instructions than keeping uniforms", "[compile]") {
    const TemplateLibrary& lib = test::shipped_library();
    VariantOptions none, all;
    none.uniforms.mode = UniformSelection::Mode::None;
    all.uniforms.mode = UniformSelection::Mode::All;
    const auto baked = test::compile_or_fail(lib, "crt-shadow-mask", none).fragment.size();
    const auto uniforms = test::compile_or_fail(lib, "crt-shadow-mask", all).fragment.size();
    CHECK(baked < uniforms);
}

TEST_CASE("a GLSL error in a template is reported at the template's file and line", "[compile][errors]") {
    test::ScratchTemplates t;
    std::string snippet = t.read("stages/scanlines.glsl");
    // Line 8 of scanlines.glsl is inside scanlines_period (the webgpu-post preset uses it).
    std::vector<std::string> lines;
    size_t start = 0;
    for (size_t i = 0; i < 7; ++i) start = snippet.find('\n', start) + 1;
    snippet.insert(start, "    float broken = undefinedThing;\n");
    t.write("stages/scanlines.glsl", snippet);
    auto lib = t.load();
    REQUIRE(lib.ok());
    auto compiled = compile_variant(*lib.value(), *lib.value()->find_preset("webgpu-post"), {}, Cache());
    REQUIRE_FALSE(compiled.ok());
    CHECK_THAT(compiled.error().file, Catch::EndsWith("stages/scanlines.glsl"));
    CHECK(compiled.error().line == 8);
    CHECK_THAT(compiled.error().message, Catch::Contains("undefinedThing"));
    CHECK(compiled.error().kind == ErrorKind::Input);
}

TEST_CASE("compile_to_spirv reports errors of sources without #line", "[compile][errors]") {
    CompileOptions options;
    options.source_name = "inline.frag";
    auto r = compile_to_spirv("#version 450\nvoid main() {\n  int x = ;\n}\n", options);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().file == "inline.frag");
    CHECK(r.error().line == 3);
}

TEST_CASE("sources that differ only in #line file names and comments give one module, a code change another", "[compile]") {
    // The optimised-module memo is keyed by glslang's output without debug info: the file names a
    // #line gives and comments do not count, the code does; a failure keeps its own file name.
    auto source = [](const std::string& file, const std::string& comment, const std::string& gain) {
        return "#version 450\n#extension GL_GOOGLE_cpp_style_line_directive : require\n#line 1 \"" + file + "\"\n// " + comment +
               "\nlayout(location = 0) in vec2 uv;\nlayout(location = 0) out vec4 color;\n"
               "void main() { float shade = uv.x * " + gain + "; color = vec4(shade, uv.y, 0.0, 1.0); }\n";
    };
    CompileOptions options;
    auto a = compile_to_spirv(source("/tmp/one/pass0.frag", "preset one", "0.5"), options);
    auto b = compile_to_spirv(source("/tmp/two/pass7.frag", "preset two", "0.5"), options);
    auto c = compile_to_spirv(source("/tmp/one/pass0.frag", "preset one", "0.25"), options);
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    REQUIRE(c.ok());
    CHECK(a.value() == b.value());
    CHECK(a.value() != c.value());

    const std::string broken = "#version 450\n#extension GL_GOOGLE_cpp_style_line_directive : require\n#line 1 \"/tmp/three/pass1.frag\"\nvoid main() { int x = ; }\n";
    auto first = compile_to_spirv(broken, options);
    auto again = compile_to_spirv(std::string(broken).replace(broken.find("three"), 5, "four!"), options);
    REQUIRE_FALSE(first.ok());
    REQUIRE_FALSE(again.ok());
    CHECK(first.error().file == "/tmp/three/pass1.frag");
    CHECK(again.error().file == "/tmp/four!/pass1.frag");
}

TEST_CASE("an invalid module is refused with its ids named", "[compile]") {
    // spirv-val runs without naming ids (the cost of a valid module's check); a module that
    // fails is checked again with names, so the message still says which value is wrong.
    CompileOptions options;
    options.stage = ShaderStage::Fragment;
    options.optimize = false;
    options.source_name = "<named>";
    auto spirv = compile_to_spirv("#version 450\nlayout(location = 0) out vec4 outColour;\nvoid main() { outColour = vec4(0.5); }\n", options);
    REQUIRE(spirv.ok());
    SpirvBinary broken = spirv.value();
    const auto list = detail::spirv_instructions(broken);
    REQUIRE(list);
    bool stored = false;
    for (const detail::SpirvInstruction& in : *list)
        if (in.opcode == spv::OpStore && in.count == 3) {
            broken[in.offset + 2] = broken[in.offset + 1];  // store the pointer into itself: a type mismatch
            stored = true;
        }
    REQUIRE(stored);
    const Status valid = validate_spirv(broken);
    REQUIRE_FALSE(valid.ok());
    CHECK_THAT(valid.error().message, Catch::Contains("spirv-val") && Catch::Contains("%outColour"));
}

TEST_CASE("an array too long for one SPIR-V instruction is refused at its line", "[compile][hostile]") {
    // glslang writes an initialiser of more than 65532 elements as an instruction whose 16-bit
    // word count wraps; the error names the declaration, through the source's #line directives,
    // whether glslang keeps a tree node of it (an array a function builds) or not (a global const).
    std::string elements;
    for (int i = 0; i < 70000; ++i) elements += i ? ", 0.5" : "0.5";
    CompileOptions options;
    options.stage = ShaderStage::Fragment;
    options.source_name = "<generated>";
    const std::string head = "#version 450\n#extension GL_GOOGLE_cpp_style_line_directive : require\n#line 1 \"big.glsl\"\nlayout(location = 0) out vec4 o;\n";
    for (const std::string& body :
         {"const float big[70000] = float[70000](" + elements + ");\nvoid main() { o = vec4(0.5); }\n",
          "void main() {\n    float big[70000] = float[70000](" + elements + ");\n    o = vec4(big[int(gl_FragCoord.x)]);\n}\n"}) {
        auto spirv = compile_to_spirv(head + body, options);
        REQUIRE_FALSE(spirv.ok());
        CHECK(spirv.error().file == "big.glsl");
        CHECK(spirv.error().line == (body.rfind("const", 0) == 0 ? 2 : 3));
        CHECK_THAT(spirv.error().message, Catch::Contains("more than 65532 elements"));
    }
}
