// clamp(x, lo, hi) with bounds that are not constants in order reaches spirv-opt as min(max()), the
// formula GLSL defines it by and drivers compute (generator/spirv_clamp_lowering.cpp): checked in
// the module's text, and by rendering the optimised module on lavapipe against glslang's own.
#include <catch2/catch.hpp>

#include <string>

#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;

// RetroArch's Advanced_CRT_shader_whkrmrgks0 writes clamp(0.0, 1.0, t) for clamp(t, 0.0, 1.0): lo
// above hi wherever t < 1. t runs over the columns from -0.5 to 1.5.
const char* kSwappedClamp = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
void main() {
    float t = vTexCoord.x * 2.0 - 0.5;
    fragColor = vec4(clamp(0.0, 1.0, t), clamp(t, 0.8, 0.2), clamp(t, 0.0, 1.0), 1.0);
}
)";

}  // namespace

TEST_CASE("a clamp with bounds not known to be in order becomes min(max()), an ordered one stays clamp", "[compile][clamp]") {
    const std::string text = disassemble_spirv(test::compile_glsl_or_fail(R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform P { float lo; int n; } p;
void main() {
    vec4 v = vec4(vTexCoord, vTexCoord * 3.0);
    ivec2 i = ivec2(vTexCoord * 8.0);
    fragColor = clamp(v, 0.0, 1.0)                                   // ordered constants, smeared: stays
              + vec4(clamp(vTexCoord.x, p.lo, 1.0))                  // a uniform bound: min(max())
              + vec4(clamp(vTexCoord.y, 0.9, 0.1))                   // swapped constants: min(max())
              + vec4(vec2(clamp(i, ivec2(0), ivec2(p.n, 4))), 0.0, 0.0);  // a uniform integer bound
}
)", ShaderStage::Fragment, true));
    INFO(text);
    CHECK(test::count_of(text, " FClamp ") == 1);
    CHECK(test::count_of(text, " SClamp ") == 0);
    CHECK(test::count_of(text, " FMin ") >= 2);
    CHECK(test::count_of(text, " SMin ") >= 1);
}

TEST_CASE("swapped clamp bounds draw the same once optimised as glslang's module draws, on lavapipe", "[compile][clamp][runtime][vulkan]") {
    auto engine = create_vulkan_engine(EngineOptions{"", /*validation*/ true});
    INFO((engine.ok() ? std::string() : engine.error().str()));
    REQUIRE(engine.ok());
    constexpr int width = 64;
    Image drawn[2];
    for (bool optimize : {false, true})
        drawn[optimize] = test::draw_fragment(*engine.value(), test::compile_glsl_or_fail(kSwappedClamp, ShaderStage::Fragment, optimize),
                                              optimize, width, 1);
    for (int px = 0; px < width; ++px) {
        const double t = (px + 0.5) / width * 2.0 - 0.5;
        INFO("t = " << t);
        for (int ch = 0; ch < 3; ++ch) CHECK(drawn[1].pixel(px, 0)[ch] == drawn[0].pixel(px, 0)[ch]);
        CHECK(drawn[1].pixel(px, 0)[0] == Approx(std::min(1.0, t)).margin(2e-3));  // min(max(0, 1), t)
        CHECK(drawn[1].pixel(px, 0)[1] == Approx(0.2).margin(1e-3));               // min(max(t, 0.8), 0.2)
    }
}
