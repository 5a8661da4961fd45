// GLSL 450 assembly -> SPIR-V: every preset compiles and validates; template errors point at the
// template file and line.
#include <catch2/catch.hpp>

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
