// Every target output is consumed by a real compiler: GLSL re-parsed by glslang in its desktop and
// ES profiles, HLSL re-compiled through glslang's HLSL front end to SPIR-V.
#include <algorithm>

#include <catch2/catch.hpp>

#include "crtforge/validate/target_render.hpp"
#include "targets/float_literals.hpp"
#include "targets/word_scan.hpp"
#include "targets/spirv_gather_lowering.hpp"
#include "targets/glsl/glsl_writer.hpp"
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

TEST_CASE("the emitters' word scans rewrite whole words and whole member accesses only", "[targets][readable]") {
    using crtforge::detail::replace_member_access;
    using crtforge::detail::rewrite_words;
    auto ids = [](std::string_view w) -> std::optional<std::string> {
        if (w.size() > 1 && w[0] == '_' && w.find_first_not_of("0123456789", 1) == std::string_view::npos) return "_v" + std::string(w.substr(1));
        return std::nullopt;
    };
    CHECK(rewrite_words("_12 = a_12 + _12x + _3.x + (_45);", ids) == "_v12 = a_12 + _12x + _v3.x + (_v45);");
    CHECK(rewrite_words("", ids).empty());
    CHECK(rewrite_words("_7", ids) == "_v7");
    auto block = [](const std::string& m) { return "U_" + m; };
    CHECK(replace_member_access("ubo.a + myubo.b + ubo.c1.x + ubo. d + ubo.", "ubo", block) == "U_a + myubo.b + U_c1.x + ubo. d + ubo.");
    CHECK(replace_member_access("f(ubo.ubo.a)", "ubo", block) == "f(U_ubo.a)");
}

TEST_CASE("a component of a constant splat prints as the constant", "[targets][readable]") {
    using crtforge::detail::without_splat_selects;
    CHECK(without_splat_selects("o = vec4(c.x ? vec4(0.0).x : v.x, c.y ? vec3(-1.5).y : v.y);") == "o = vec4(c.x ? 0.0 : v.x, c.y ? (-1.5) : v.y);");
    CHECK(without_splat_selects("o = float4(c.x ? 0.0f.xxxx.x : v.x, c.w ? 2.5f.xxx.z : v.w);") == "o = float4(c.x ? 0.0f : v.x, c.w ? 2.5f : v.w);");
    CHECK(without_splat_selects("x = vec4(1e-05).w;") == "x = 1e-05;");
    // Left as they are: not a splat of one literal, a selection of more than one component or
    // followed by more, integer and boolean vectors, words that end in vec, comments.
    for (const char* kept : {"vec4(a).x", "vec4(0.0, 1.0).x", "vec4(0.0).xy", "vec4(0.0).x.x", "ivec4(0).x", "dvec2(0.0).x",
                             "myvec4(0.0).x", "v.vec4(0.0).x", "0.0f.xxxx", "0.0f.xxxx.xy", "s.f0.xxxx.x", "// vec4(0.0).x\n",
                             "#define Z vec4(0.0).x\n", "vec4(0.0).x_"})
        CHECK(without_splat_selects(kept) == kept);
}

TEST_CASE("float constants print at the shortest text that reads back as the same float32", "[targets][readable]") {
    using crtforge::detail::shorten_float_literals;
    CHECK(shorten_float_literals("x = 0.300000011920928955078125 * y;") == "x = 0.3 * y;");
    CHECK(shorten_float_literals("sin(a * 3.141590118408203125)") == "sin(a * 3.14159)");
    CHECK(shorten_float_literals("float h = 0.300000011920928955078125f;") == "float h = 0.3f;");  // HLSL
    CHECK(shorten_float_literals("-0.699999988079071044921875") == "-0.7");
    // Left as they are: doubles that no float32 equals, suffixes other than f, exponents, integers,
    // identifiers with digits, comments and preprocessor lines, literals already short.
    for (const char* kept : {"double d = 0.1000000000000000055511151231257827;", "0.300000011920928955078125lf",
                             "9.9999997473787516355514526367188e-06", "int i = 12345678901;", "vec2 _342 = v;",
                             "// 0.300000011920928955078125\n", "#define K 0.300000011920928955078125\n", "x = 2.0; y = 0.5;"})
        CHECK(shorten_float_literals(kept) == kept);
    // Every export of every preset through SPIRV-Cross: no literal left that could be shorter.
    const TemplateLibrary& lib = test::shipped_library();
    for (const Preset& p : lib.presets()) {
        CompiledVariant c = test::compile_or_fail(lib, p.name);
        for (TargetId t : {TargetId::Glsl450, TargetId::Glsl330, TargetId::GlslEs300, TargetId::Hlsl50, TargetId::Godot3, TargetId::Godot4}) {
            auto out = emit_target(c, t, Cache());
            REQUIRE(out.ok());
            for (const OutputFile& f : out.value().files) {
                INFO(p.name << " " << f.suffix);
                CHECK(shorten_float_literals(f.data) == f.data);
                CHECK(f.data.find(".300000011920928955078125") == std::string::npos);
            }
        }
    }
}

TEST_CASE("the webgl2 target declares params and builtins as plain uniforms set by name", "[targets][webgl2]") {
    const TemplateLibrary& lib = test::shipped_library();
    const CompiledVariant classic = test::compile_or_fail(lib, "classic");
    auto out = emit_target(classic, TargetId::WebGl2, Cache());
    REQUIRE(out.ok());
    const std::string fragment = out.value().files.back().data;
    INFO(fragment);
    CHECK_THAT(fragment, Catch::StartsWith("#version 300 es\n"));
    for (const char* line : {"uniform vec2 outputSize;", "uniform float scanlineIntensity;", "uniform vec3 bezelColor;",
                             "uniform highp sampler2D source;"})
        CHECK_THAT(fragment, Catch::Contains(line));
    CHECK_THAT(fragment, !Catch::Contains("CrtParams"));
    CHECK_THAT(fragment, !Catch::Contains("crtforge_plain_block"));
    CHECK_THAT(fragment, Catch::Contains("(curvature * r2 + 1.0)"));  // members read by their own name
    // The manifest tells a host how to set each one.
    bool names_param = false;
    for (const auto& b : out.value().bindings) names_param = names_param || b.first == "scanlineIntensity";
    CHECK(names_param);

    // Medium precision: members keep their qualifiers as top-level uniforms.
    using crtforge::glsl::flatten_plain_uniform_block;
    const std::string text = "#version 300 es\nstruct CrtParams\n{\n    mediump float gain;\n    highp vec2 outputSize;\n};\n\n"
                             "uniform CrtParams blk;\n\nvoid main() { x = blk.gain * blk.outputSize.x; }\n";
    CHECK(flatten_plain_uniform_block(text, "blk") ==
          "#version 300 es\nuniform mediump float gain;\nuniform highp vec2 outputSize;\n\nvoid main() { x = gain * outputSize.x; }\n");
}

TEST_CASE("textureGather lowered to four reads is a valid module, and a gather with offsets is left as it was", "[targets][gather]") {
    const char* gathers = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() {
    fragColor = textureGather(source, vTexCoord, 0) * 0.5 + textureGather(source, vTexCoord.yx, 2) * 0.5;
}
)";
    for (bool optimize : {false, true}) {
        SpirvBinary module = test::compile_glsl_or_fail(gathers, ShaderStage::Fragment, optimize);
        CHECK(crtforge::detail::lower_texture_gathers(module) == 2);
        const auto valid = validate_spirv(module);
        INFO((valid.ok() ? std::string() : valid.error().str()));
        CHECK(valid.ok());
    }
    const char* offset = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() { fragColor = textureGatherOffset(source, vTexCoord, ivec2(1, 0), 1); }
)";
    const SpirvBinary before = test::compile_glsl_or_fail(offset, ShaderStage::Fragment, true);
    SpirvBinary after = before;
    CHECK(crtforge::detail::lower_texture_gathers(after) == 0);
    CHECK(after == before);
}
