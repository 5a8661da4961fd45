// Arrays of arrays flattened for GLSL 3.30 / ES 3.00 and Godot (targets/spirv_flat_arrays.cpp): the
// flat module is valid SPIR-V with no array of arrays left, SPIRV-Cross then writes GLSL ES 3.00
// for it, and it draws on lavapipe what glslang's own module draws, for every way a shader reaches
// into such an array.
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include <spirv_cross/spirv_cross_error_handling.hpp>
#include <spirv_cross/spirv_glsl.hpp>

#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "targets/spirv_flat_arrays.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;

// A constant 2-D table read at variable indices (crt-geom's masks), a 3-D one, a local 2-D array
// written element by element and row by row, a row read whole (a pointer that stops at a row), a
// row taken out of and put into a value (extract / insert), and arrays built from rows.
const char* kTables = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
const vec3 kMasks[3][2] = vec3[3][2](vec3[2](vec3(1.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0)),
                                     vec3[2](vec3(0.5), vec3(0.25, 0.0, 0.75)),
                                     vec3[2](vec3(0.0, 0.0, 1.0), vec3(1.0, 1.0, 0.0)));
const float kCube[2][3][2] = float[2][3][2](float[3][2](float[2](0.1, 0.2), float[2](0.3, 0.4), float[2](0.5, 0.6)),
                                            float[3][2](float[2](0.7, 0.8), float[2](0.9, 1.0), float[2](0.15, 0.25)));
void main() {
    int i = int(vTexCoord.x * 2.99), j = int(vTexCoord.y * 1.99), k = int(vTexCoord.x * 5.99) % 3;
    vec3 mask = kMasks[i][j];
    float cube = kCube[j][k][i % 2];
    float local[4][3];
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 3; ++b) local[a][b] = float(a * 3 + b) / 12.0;
    float row[3] = local[i + 1];
    local[j] = float[3](vTexCoord.x, vTexCoord.y, 0.5);
    vec3 pair[2] = kMasks[(i + j) % 3];
    vec3 grid[2][2] = vec3[2][2](pair, vec3[2](mask, vec3(cube)));
    grid[1] = pair;
    vec3 picked[2] = grid[j];
    fragColor = vec4(mask.r * 0.5 + cube * 0.5, row[k] + local[j][1] * 0.25, picked[1 - j].b * 0.5 + grid[0][i % 2].g * 0.25, 1.0);
}
)";

}  // namespace

TEST_CASE("arrays of arrays become flat arrays in valid SPIR-V that SPIRV-Cross writes as GLSL ES 3.00", "[compile][flat-arrays]") {
    for (bool optimize : {false, true}) {
        INFO("optimised: " << optimize);
        SpirvBinary words = test::compile_glsl_or_fail(kTables, ShaderStage::Fragment, optimize);
        CHECK(detail::flatten_arrays_of_arrays(words) >= 3);  // [3][2], [2][3][2] and its [3][2] rows, [4][3], [2][2]
        const std::string text = disassemble_spirv(words);
        static const std::regex array_of_arrays(R"((%\w+) = OpTypeArray %_arr_)");
        CHECK_FALSE(std::regex_search(text, array_of_arrays));
        const Status valid = validate_spirv(words);
        INFO((valid.ok() ? std::string() : valid.error().str()));
        CHECK(valid.ok());
        SpirvBinary again = words;
        CHECK(detail::flatten_arrays_of_arrays(again) == 0);
        CHECK(again == words);
        spirv_cross::CompilerGLSL glsl(words);
        auto options = glsl.get_common_options();
        options.version = 300;
        options.es = true;
        glsl.set_common_options(options);
        std::string es;
        REQUIRE_NOTHROW(es = glsl.compile());
        INFO(es);
        CHECK(es.find("][") == std::string::npos);
    }
}

TEST_CASE("flattened arrays of arrays draw on lavapipe what glslang's module draws", "[compile][flat-arrays][runtime][vulkan]") {
    auto engine = create_vulkan_engine(EngineOptions{"", /*validation*/ true});
    INFO((engine.ok() ? std::string() : engine.error().str()));
    REQUIRE(engine.ok());
    for (bool optimize : {false, true}) {
        INFO("optimised: " << optimize);
        const SpirvBinary glslang = test::compile_glsl_or_fail(kTables, ShaderStage::Fragment, optimize);
        SpirvBinary flat = glslang;
        REQUIRE(detail::flatten_arrays_of_arrays(flat) >= 3);
        const Image expected = test::draw_fragment(*engine.value(), glslang, optimize, 48, 8);
        test::check_same_picture(test::draw_fragment(*engine.value(), flat, optimize, 48, 8), expected, 0.0);
        int varied = 0;  // the indices vary across the picture
        for (int y = 0; y < expected.height; ++y)
            for (int x = 0; x < expected.width; ++x) varied += expected.pixel(x, y)[0] != expected.pixel(0, 0)[0];
        CHECK(varied > expected.width * expected.height / 2);
    }
}

TEST_CASE("an array of arrays in a uniform block is refused by name: its layout is the host's", "[compile][flat-arrays]") {
    SpirvBinary words = test::compile_glsl_or_fail(R"(#version 450
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform P { vec4 table[2][2]; } p;
void main() { fragColor = p.table[1][0]; }
)", ShaderStage::Fragment, true);
    const SpirvBinary before = words;
    try {
        detail::flatten_arrays_of_arrays(words);
        FAIL("no refusal");
    } catch (const spirv_cross::CompilerError& e) {
        CHECK(std::string(e.what()).find("uniform or storage block") != std::string::npos);
    }
    CHECK(words == before);
}
