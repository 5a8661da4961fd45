// Every target output is consumed by a real compiler: GLSL re-parsed by glslang in its desktop and
// ES profiles, HLSL re-compiled through glslang's HLSL front end to SPIR-V.
#include <algorithm>

#include <catch2/catch.hpp>

#include "crtforge/validate/target_render.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;


TEST_CASE("every preset x target is accepted by the target's consumer", "[targets]") {
    const TemplateLibrary& lib = test::shipped_library();
    for (const Preset& p : lib.presets()) {
        for (Precision precision : {Precision::High, Precision::Medium}) {
            VariantOptions options;
            options.precision = precision;
            CompiledVariant c = test::compile_or_fail(lib, p.name, options);
            for (const TargetInfo& t : all_targets()) {
                auto out = emit_target(c, t.id, Cache());
                INFO(p.name << " -> " << t.name << " (" << precision_name(precision) << ")");
                REQUIRE(out.ok());
                size_t shaders = 0;
                for (const OutputFile& f : out.value().files) shaders += f.is_shader();
                REQUIRE(shaders == t.shader_roles.size());
                for (const OutputFile& f : out.value().files)
                    if (f.is_shader()) CHECK(std::count(t.shader_roles.begin(), t.shader_roles.end(), f.manifest_role()) == 1);
                for (const OutputFile& f : out.value().files) {
                    INFO(shader_stage_name(f.stage) << " shader:\n" << f.data);
                    auto consumed = consume_output(t.id, f);
                    CHECK(consumed.ok());
                    if (!consumed.ok()) WARN(consumed.error().str());
                }
            }
        }
    }
}

TEST_CASE("outputs use the spec's param names, not generated ids", "[targets]") {
    const TemplateLibrary& lib = test::shipped_library();
    CompiledVariant c = test::compile_or_fail(lib, "crt-shadow-mask");
    auto text = [&](TargetId t) { return emit_target(c, t, Cache()).value().files.back().data; };
    CHECK_THAT(text(TargetId::Glsl450), Catch::Contains("crt.maskSize"));
    CHECK_THAT(text(TargetId::Glsl330), Catch::Contains("uniform CrtParams"));
    CHECK_THAT(text(TargetId::GlslEs300), Catch::Contains("crt.scanlineIntensity"));
    CHECK_THAT(text(TargetId::GlslEs300), Catch::Contains("precision highp float"));
    CHECK_THAT(text(TargetId::Hlsl50), Catch::Contains("crt_maskIntensity"));
    CHECK_THAT(text(TargetId::Hlsl60), Catch::Contains("cbuffer CrtParams"));
    for (TargetId t : {TargetId::Glsl450, TargetId::Glsl330, TargetId::GlslEs300})
        CHECK_THAT(text(t), !Catch::Contains("} _"));  // no anonymous "_19" block instance
}

TEST_CASE("vertex shaders for y-up APIs are flipped, SPIR-V is not", "[targets]") {
    const TemplateLibrary& lib = test::shipped_library();
    CompiledVariant c = test::compile_or_fail(lib, "passthrough");
    const std::string glsl = emit_target(c, TargetId::Glsl330, Cache()).value().files.front().data;
    CHECK_THAT(glsl, Catch::Contains("gl_VertexID"));
    CHECK_THAT(glsl, Catch::Contains("gl_Position.y = -gl_Position.y"));
    const std::string hlsl = emit_target(c, TargetId::Hlsl50, Cache()).value().files.front().data;
    CHECK_THAT(hlsl, Catch::Contains("SV_VertexID"));
    CHECK_THAT(hlsl, Catch::Contains("gl_Position.y = -gl_Position.y"));
}
