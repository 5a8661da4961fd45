// pow() with a constant exponent leaves the generator as square roots and products
// (generator/spirv_pow_reduction.cpp): checked in the module's text, and by rendering the rewritten
// module on lavapipe against std::pow.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;

// x runs over the output's columns: x = (column + 0.5) / width * 2 - 0.5, so some bases are negative.
std::string powers_shader(const std::string& e0, const std::string& e1, const std::string& e2, const std::string& e3) {
    return "#version 450\n"
           "layout(location = 0) in vec2 vTexCoord;\n"
           "layout(location = 0) out vec4 fragColor;\n"
           "void main() {\n"
           "    float x = vTexCoord.x * 2.0 - 0.5;\n"
           "    fragColor = vec4(pow(x, " + e0 + "), pow(x, " + e1 + "), pow(x, " + e2 + "), pow(x, " + e3 + "));\n"
           "}\n";
}

}  // namespace

TEST_CASE("pow with a constant exponent becomes sqrt and products, the others stay pow", "[compile][pow]") {
    const std::string text = disassemble_spirv(test::compile_glsl_or_fail(R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform P { float e; } p;
void main() {
    float x = vTexCoord.x;
    vec3 v = vec3(vTexCoord, x);
    vec3 a = pow(v, vec3(1.5)) + pow(v, vec3(2.0, 2.0, 3.0));  // a mixed vector exponent stays pow
    fragColor = vec4(a, pow(x, 0.5) + pow(x, 2.5) + pow(x, 4.0) + pow(x, -0.5) + pow(x, 1.7) + pow(x, p.e));
}
)", ShaderStage::Fragment));
    INFO(text);
    CHECK(test::count_of(text, " Pow ") == 3);           // vec3(2, 2, 3), 1.7 and the uniform
    CHECK(test::count_of(text, " Sqrt ") == 3);          // 1.5, 0.5, 2.5
    CHECK(test::count_of(text, " InverseSqrt ") == 1);   // -0.5
    CHECK(test::count_of(text, "OpFMul") >= 4);          // x*sqrt(x), x*x and x*x*sqrt(x), (x*x)^2
}

TEST_CASE("the rewritten powers compute what std::pow does, on lavapipe", "[compile][pow][runtime][vulkan]") {
    auto engine = create_vulkan_engine(EngineOptions{"", /*validation*/ true});
    INFO((engine.ok() ? std::string() : engine.error().str()));
    REQUIRE(engine.ok());
    const int width = 32;
    struct Case {
        std::array<std::string, 4> glsl;
        std::array<double, 4> exponent;
    };
    for (const Case& c : {Case{{"0.5", "1.5", "2.0", "2.5"}, {0.5, 1.5, 2.0, 2.5}},
                          Case{{"3.0", "4.0", "-0.5", "1.7"}, {3.0, 4.0, -0.5, 1.7}}}) {
        const Image out = test::draw_fragment(
            *engine.value(), test::compile_glsl_or_fail(powers_shader(c.glsl[0], c.glsl[1], c.glsl[2], c.glsl[3]), ShaderStage::Fragment),
            /*optimize: the generator's*/ true, width, 1);
        for (int px = 0; px < width; ++px) {
            const double x = (px + 0.5) / width * 2.0 - 0.5;
            for (int ch = 0; ch < 4; ++ch) {
                const double want = std::pow(x, c.exponent[ch]);
                const float got = out.pixel(px, 0)[ch];
                INFO("pow(" << x << ", " << c.exponent[ch] << ") = " << got << ", std::pow " << want);
                if (std::isnan(want)) {
                    CHECK(std::isnan(got));  // a negative base to a fractional power, as pow gives
                } else if (std::isinf(want)) {
                    CHECK(std::isinf(got));
                } else {
                    CHECK(std::abs(got - want) <= 2e-3 * std::max(1.0, std::abs(want)));  // half-float output
                }
            }
        }
    }
}
