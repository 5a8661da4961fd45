// Godot 3's parser needs more than Godot 4's (targets/godot/godot3_syntax.cpp): each rewrite on the
// text shapes SPIRV-Cross prints. Real Godot 3 runs the rewritten shaders in the corpus tests.
#include <catch2/catch.hpp>

#include <spirv_cross/spirv_common.hpp>

#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "targets/godot/godot3_syntax.hpp"
#include "targets/godot/spirv_constant_indices.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
using namespace crtforge::godot::godot3;

TEST_CASE("Godot 3: global const arrays are declared in each function that reads them", "[godot][godot3-syntax]") {
    const std::string text = "shader_type canvas_item;\n"
                             "const float _12[3] = float[](1.0, 2.0, 3.0);\n"
                             "const vec2 _20[2] = vec2[](vec2(0.5), vec2(1.0));\n"
                             "struct S\n{\n    float a;\n};\n"
                             "float pick(int i)\n{\n    return _12[i];\n}\n"
                             "void fragment()\n{\n    COLOR = vec4(_20[1], pick(2), _12[0]);\n}\n";
    const std::string out = with_constant_arrays_local(text);
    CHECK(out.find("\nconst ") == std::string::npos);
    CHECK(out == "shader_type canvas_item;\n"
                 "struct S\n{\n    float a;\n};\n"
                 "float pick(int i)\n{\n    float _12[3] = float[](1.0, 2.0, 3.0);\n    return _12[i];\n}\n"
                 "void fragment()\n{\n    float _12[3] = float[](1.0, 2.0, 3.0);\n    vec2 _20[2] = vec2[](vec2(0.5), vec2(1.0));\n"
                 "    COLOR = vec4(_20[1], pick(2), _12[0]);\n}\n");
    CHECK(with_constant_arrays_local("void fragment()\n{\n}\n") == "void fragment()\n{\n}\n");
}

TEST_CASE("Godot 3: a comma list of loop steps runs at the end of the body and before each of its continues", "[godot][godot3-syntax]") {
    const std::string text = "    for (int i = 0; i < 4; j = k, i++)\n"
                             "    {\n"
                             "        if (i == 1)\n"
                             "        {\n"
                             "            continue;\n"
                             "        }\n"
                             "        for (int m = 0; m < 2; m++)\n"
                             "        {\n"
                             "            continue;\n"
                             "        }\n"
                             "        k = i;\n"
                             "    }\n";
    CHECK(with_loop_steps_in_body(text) == "    for (int i = 0; i < 4; )\n"
                                          "    {\n"
                                          "        if (i == 1)\n"
                                          "        {\n"
                                          "            { j = k; i++; continue; }\n"
                                          "        }\n"
                                          "        for (int m = 0; m < 2; m++)\n"
                                          "        {\n"
                                          "            continue;\n"  // the inner loop's own
                                          "        }\n"
                                          "        k = i;\n"
                                          "        j = k; i++;\n"
                                          "    }\n");
    // A single step is Godot 3's own syntax: untouched.
    const std::string single = "for (int i = 0; i < 4; i++)\n{\n}\n";
    CHECK(with_loop_steps_in_body(single) == single);
    CHECK_THROWS_AS(with_loop_steps_in_body("for (int i = 0; i < 4; j = k, i++)\n    x = 1;\n"), spirv_cross::CompilerError);
}

TEST_CASE("Godot 3: loops get an initialiser, a step and a condition, unsigned literals a type", "[godot][godot3-syntax]") {
    CHECK(with_loop_increments("for (int i = 0; i < 4; )") == "for (int i = 0; i < 4; i += 0)");
    CHECK(with_loop_increments("for (;;)") == "for (int crtforge_loop0 = 0; true; crtforge_loop0 += 0)");
    CHECK(with_loop_initialisers("for (; i_16 < 6; i_16++)\n{\n    for (; j < 2; j++)") ==
          "for (int crtforge_init0 = 0; i_16 < 6; i_16++)\n{\n    for (int crtforge_init1 = 0; j < 2; j++)");
    CHECK(with_godot3_syntax("for (;;)") == "for (int crtforge_loop0 = 0; true; crtforge_loop0 += 0)");  // given one already
    // Nor hexadecimal: the int of the same bits (SPIRV-Cross spells an infinity's bits so).
    CHECK(with_unsigned_literals_spelled("x % 4u + 0xFFu + y2u + 10 + 0xff800000u") == "x % uint(4) + uint(255) + y2u + 10 + uint(-8388608)");
    // All of them, in order: the moved steps leave a loop that then gets its zero step.
    CHECK(with_godot3_syntax("for (int i = 0; i < 4; j = k, i++)\n{\n}\n") == "for (int i = 0; i < 4; i += 0)\n{\n    j = k; i++;\n}\n");
}

TEST_CASE("Godot 3: a float literal its six printed digits would change goes as its bits", "[godot][godot3-syntax]") {
    // Godot 3 prints constants with %g: 0.9999999 would reach the driver as 1.0, 0.083333336 as 0.0833333.
    CHECK(with_float_literals_exact("a > 0.9999999 ? 0.083333336 : 0.5;\n") ==
          "a > uintBitsToFloat(uint(1065353214)) ? uintBitsToFloat(uint(1034594987)) : 0.5;\n");
    // Kept: what six digits hold (1e-07 included), integers, suffixed literals, comments, and the
    // literals a uniform's default or a constant's initialiser must be.
    CHECK(with_float_literals_exact("x = 0.25 * 3.14159 + 1e-07 + 1024.0 + 12 + 1.5f; // 0.9999999\n") ==
          "x = 0.25 * 3.14159 + 1e-07 + 1024.0 + 12 + 1.5f; // 0.9999999\n");
    CHECK(with_float_literals_exact("uniform float k : hint_range(0.0, 1.0) = 0.9999999;\n  const float c = 0.9999999;\n") ==
          "uniform float k : hint_range(0.0, 1.0) = 0.9999999;\n  const float c = 0.9999999;\n");
}

TEST_CASE("Godot 3: an array assigned whole, assigned a constructor, or declared from another, is copied element by element", "[godot][godot3-syntax]") {
    const std::string text = "void fragment()\n{\n    float _347[3] = float[](1.0, 2.0, 3.0);\n    float phase[3] = float[](0.0, 0.0, 0.0);\n"
                             "    float x = 1.0;\n    float y;\n    if (x > 0.5)\n    {\n        phase = _347;\n    }\n    y = x;\n}\n";
    CHECK(with_array_copies_elementwise(text) ==
          "void fragment()\n{\n    float _347[3] = float[](1.0, 2.0, 3.0);\n    float phase[3] = float[](0.0, 0.0, 0.0);\n"
          "    float x = 1.0;\n    float y;\n    if (x > 0.5)\n    {\n"
          "        for (int crt_element = 0; crt_element < 3; crt_element++) { phase[crt_element] = _347[crt_element]; }\n    }\n    y = x;\n}\n");
    // A declaration initialised from another array (nis's scaler) is declared, then copied.
    CHECK(with_array_copies_elementwise("{\n    float a[6];\n    float b[6] = a;\n    float c = d;\n}\n") ==
          "{\n    float a[6];\n    float b[6];\n    for (int crt_element = 0; crt_element < 6; crt_element++) { b[crt_element] = a[crt_element]; }\n"
          "    float c = d;\n}\n");
    // An array assigned a constructor (crt-guest-advanced-pal's PalPass3) gets each argument; a
    // constructor of another length, or a name that is no array, is left as it is.
    CHECK(with_array_copies_elementwise("{\n    float a[3];\n    if (x)\n    {\n        a = float[](1.0, f(2.0, 3.0), -0.5);\n    }\n"
                                        "    a = float[](1.0, 2.0);\n    v = vec2[](u, u);\n}\n") ==
          "{\n    float a[3];\n    if (x)\n    {\n        a[0] = 1.0;\n        a[1] = f(2.0, 3.0);\n        a[2] = -0.5;\n    }\n"
          "    a = float[](1.0, 2.0);\n    v = vec2[](u, u);\n}\n");
}

TEST_CASE("Godot 3: a loop declaring several variables declares all but its first before it", "[godot][godot3-syntax]") {
    CHECK(with_loop_declarations_single("{\n        for (float a = f(1.0, 2.0), b = c, d; a < 1.0; a += 0.5)\n        {\n        }\n"
                                        "    for (int i = 0; i < 2; i++)\n    {\n    }\n}\n") ==
          "{\n        float b = c;\n        float d;\n        for (float a = f(1.0, 2.0); a < 1.0; a += 0.5)\n        {\n        }\n"
          "    for (int i = 0; i < 2; i++)\n    {\n    }\n}\n");
}

TEST_CASE("Godot 3: a negated subtrahend is added", "[godot][godot3-syntax]") {
    // Godot 3 prints `a - (-1.0)` to GLSL as `(a--1.0)`, a decrement to the GL driver (tvout-tweaks).
    CHECK(with_negated_subtrahends_added("    float _1746 = _1720 - (-1.0);\n") == "    float _1746 = _1720 + 1.0;\n");
    CHECK(with_negated_subtrahends_added("x = a - (-b.xy) * c - -d[2] - (-1.5e-05);\n") == "x = a + b.xy * c + d[2] + 1.5e-05;\n");
    // Not a whole operand, or not a subtraction: left alone.
    for (const std::string kept : {"x = a - (-b + c);\n", "x = a - (-b[1]);\n", "x = -(-a);\n", "x = a + (-b);\n", "x = a - b;\n"})
        CHECK(with_negated_subtrahends_added(kept) == kept);
}

TEST_CASE("Godot 3: a vector indexed by a loop counter is unrolled to constant indices, drawing what glslang's module draws",
          "[godot][godot3][compile][runtime][vulkan]") {
    const char* source = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
void main() {
    vec3 base = vec3(vTexCoord, 1.0 - vTexCoord.x);
    vec3 lifted;
    for (int i = 0; i < 3; ++i) lifted[i] = pow(base[i], 1.0 + 0.5 * float(i));
    mat3 m = mat3(base, lifted, base.zxy);
    vec3 columns = vec3(0.0);
    for (int i = 0; i < 3; ++i) columns += m[i] * 0.25;
    fragColor = vec4(lifted * 0.5 + columns * 0.5, 1.0);
}
)";
    const SpirvBinary glslang = test::compile_glsl_or_fail(source, ShaderStage::Fragment, true);
    REQUIRE(godot::has_variable_vector_index(glslang));
    SpirvBinary unrolled = glslang;
    REQUIRE(godot::with_loops_unrolled_for_constant_indices(unrolled));
    CHECK_FALSE(godot::has_variable_vector_index(unrolled));
    const Status valid = validate_spirv(unrolled);
    INFO((valid.ok() ? std::string() : valid.error().str()));
    CHECK(valid.ok());
    SpirvBinary again = unrolled;
    CHECK_FALSE(godot::with_loops_unrolled_for_constant_indices(again));  // nothing left: untouched
    CHECK(again == unrolled);
    auto engine = create_vulkan_engine(EngineOptions{"", /*validation*/ true});
    INFO((engine.ok() ? std::string() : engine.error().str()));
    REQUIRE(engine.ok());
    test::check_same_picture(test::draw_fragment(*engine.value(), unrolled, true, 48, 8),
                             test::draw_fragment(*engine.value(), glslang, true, 48, 8), 1e-3);
}
