// Non-square matrices padded to the square ones Godot has (targets/godot/spirv_square_matrices.cpp):
// the padded module is valid SPIR-V with no non-square matrix left, and draws on lavapipe what
// glslang's own module draws, for every way a shader hands a vector or a column across a matrix.
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include <spirv_cross/spirv_cross_error_handling.hpp>

#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "targets/godot/spirv_square_matrices.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;

// Every construct: construct from columns, matrix * vector and vector * matrix (mat4x3: the result
// shrinks; mat2x3: the vector pads), a column read and written through a variable index, a
// constant matrix and its column, an array of matrices, transpose, outerProduct, and square
// matrices of the same sizes declared before (mat4) and after (mat3) the padded ones, which the
// pass merges into one type each. Values stay near [0, 1] so a 16-bit float target keeps them.
const char* kMatrices = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
const mat4x3 kColours = mat4x3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0), vec3(0.5));
void main() {
    vec4 w = vec4(vTexCoord, 1.0 - vTexCoord.x, vTexCoord.y * 0.5) * 0.5;
    mat4 square = mat4(w, w.yzwx, w.zwxy, w.wxyz);
    vec4 s = square * vec4(0.25);
    mat4x3 m = mat4x3(vec3(vTexCoord, 0.2), vec3(0.3, vTexCoord.yx), vec3(0.1), vec3(vTexCoord.x));
    vec3 blend = m * w;
    vec4 lumas = vec3(0.299, 0.587, 0.114) * m;
    mat2x3 thin = mat2x3(blend, lumas.xyz);
    vec3 t = thin * vTexCoord;
    mat3x2 turned = transpose(thin);
    vec2 u = turned * blend;
    int i = int(vTexCoord.x * 2.99);
    mat3x2 xy = mat3x2(vTexCoord, vTexCoord.yx, vec2(0.25));
    xy[i] = xy[i] * 0.5;
    xy[i].y += 0.125;
    vec2 column = xy[(i + 1) % 3] + xy[i];
    mat4x2 wind[2] = mat4x2[2](mat4x2(1.0), mat4x2(vec2(0.5), vec2(0.25), vec2(0.125), vec2(1.0)));
    vec2 wv = wind[i % 2] * w;
    mat3x4 outer = outerProduct(w, blend);
    vec4 o = outer * vec3(0.2, 0.3, 0.5);
    vec3 k = kColours * w + kColours[i] * 0.25;
    mat3 late = mat3(blend, t, k);
    vec3 l = late * vec3(0.3);
    fragColor = vec4(blend.x + lumas.y + t.z + s.x, u.x + column.y + wv.x + o.w, k.z + l.y + o.x, 1.0) * 0.4;
}
)";

std::string matrix_types(const SpirvBinary& words) {
    std::string out;
    const std::string text = disassemble_spirv(words);
    static const std::regex matrix(R"(OpTypeMatrix %\w+ \d)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), matrix); it != std::sregex_iterator(); ++it) out += it->str() + "\n";
    return out;
}

}  // namespace

TEST_CASE("non-square matrices become square ones in valid SPIR-V, one type per size", "[compile][godot][matrices]") {
    for (bool optimize : {false, true}) {
        INFO("optimised: " << optimize);
        SpirvBinary words = test::compile_glsl_or_fail(kMatrices, ShaderStage::Fragment, optimize);
        const std::string before = matrix_types(words);
        INFO(before);
        CHECK(godot::square_matrices(words) == 5);  // mat4x3 mat2x3 mat3x2 mat4x2 mat3x4
        const std::string after = matrix_types(words);
        INFO(after);
        CHECK(test::count_of(after, "OpTypeMatrix") == 2);  // mat4 and mat3 only
        const std::string text = disassemble_spirv(words);
        for (const char* gone : {"v2float 3", "v2float 4", "v3float 2", "v3float 4", "v4float 3"}) CHECK(text.find(gone) == std::string::npos);
        const Status valid = validate_spirv(words);
        INFO((valid.ok() ? std::string() : valid.error().str()));
        CHECK(valid.ok());
        SpirvBinary again = words;
        CHECK(godot::square_matrices(again) == 0);  // nothing left to pad: the module is untouched
        CHECK(again == words);
    }
}

TEST_CASE("padded matrices draw on lavapipe what glslang's module draws", "[compile][godot][matrices][runtime][vulkan]") {
    auto engine = create_vulkan_engine(EngineOptions{"", /*validation*/ true});
    INFO((engine.ok() ? std::string() : engine.error().str()));
    REQUIRE(engine.ok());
    for (bool optimize : {false, true}) {
        INFO("optimised: " << optimize);
        const SpirvBinary glslang = test::compile_glsl_or_fail(kMatrices, ShaderStage::Fragment, optimize);
        SpirvBinary padded = glslang;
        REQUIRE(godot::square_matrices(padded) == 5);
        test::check_same_picture(test::draw_fragment(*engine.value(), padded, optimize, 48, 8),
                                 test::draw_fragment(*engine.value(), glslang, optimize, 48, 8), 1e-3);
    }
}

TEST_CASE("a non-square matrix in a uniform block is refused by name: its layout is the host's", "[compile][godot][matrices]") {
    SpirvBinary words = test::compile_glsl_or_fail(R"(#version 450
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform P { mat4x3 blend; } p;
void main() { fragColor = vec4(p.blend * vec4(0.25), 1.0); }
)", ShaderStage::Fragment, true);
    const SpirvBinary before = words;
    try {
        godot::square_matrices(words);
        FAIL("no refusal");
    } catch (const spirv_cross::CompilerError& e) {
        CHECK(std::string(e.what()).find("uniform or storage block") != std::string::npos);
    }
    CHECK(words == before);
}
