// crtforge's SPIR-V -> WGSL emitter, one construct at a time: a GLSL fragment shader goes through
// glslang (+ spirv-opt, or not) to SPIR-V, the emitter writes WGSL, Dawn must compile it with no
// message at all, and Dawn's render must match the Vulkan render of the very same SPIR-V. The
// semantic traps (GLSL mod of negatives, reversed smoothstep edges, NaN, integer division) are fed
// through uniforms, so the optimiser cannot fold them away, and checked against known values too.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <nlohmann/json.hpp>

#include "crtforge/runtime/dawn_engine.hpp"
#include "crtforge/validate/target_render.hpp"
#include "targets/wgsl/wgsl_emitter.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
using Catch::Matchers::Contains;

constexpr int kSize = 16;

SpirvBinary compile_fragment(const std::string& body, bool optimize) {
    CompileOptions options;
    options.optimize = optimize;
    options.source_name = "<construct test>";
    const std::string source = "#version 450\n"
                               "layout(location = 0) in vec2 vTexCoord;\n"
                               "layout(location = 0) out vec4 fragColor;\n"
                               "layout(std140, set = 0, binding = 0) uniform Params { vec4 a; vec4 b; ivec4 i; } p;\n"
                               "layout(set = 0, binding = 1) uniform sampler2D source;\n" + body;
    auto spirv = compile_to_spirv(source, options);
    INFO((spirv.ok() ? std::string() : spirv.error().str()));
    REQUIRE(spirv.ok());
    return spirv.value();
}

const SpirvBinary& vertex() {
    static const SpirvBinary v = test::compile_or_fail(test::shipped_library(), "passthrough").vertex;
    return v;
}

RenderEngine& vulkan() {
    // No validation layer: several constructs leave the vertex shader's texture coordinate unread,
    // which the layer reports as a performance warning.
    static auto created = create_vulkan_engine(EngineOptions{"", false});
    REQUIRE(created.ok());
    return *created.value();
}

struct Uniforms {
    float a[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0};
    int32_t i[4] = {0, 0, 0, 0};
    std::vector<uint8_t> bytes() const {
        std::vector<uint8_t> out(48);
        std::memcpy(out.data(), a, 16);
        std::memcpy(out.data() + 16, b, 16);
        std::memcpy(out.data() + 32, i, 16);
        return out;
    }
};

// A picture with negative, HDR and ordinary values, so sampling constructs see all three.
Image input() {
    Image image = Image::make(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            image.set_pixel(x, y, {x / 8.0f - 1.0f, y / 4.0f, 0.25f, 1.0f});
    return image;
}

struct Rendered {
    std::string wgsl;
    Image dawn, vulkan;
};

// Emits, compiles in Dawn (zero messages), renders on Dawn and on Vulkan, and checks they agree.
// `vulkan_agrees = false` skips the pixel comparison with Vulkan where lavapipe departs from the
// SPIR-V specification (the known values are checked instead).
Rendered check_construct(const std::string& body, const Uniforms& u, bool optimize = true, float tolerance = 2e-3f,
                         bool vulkan_agrees = true) {
    const SpirvBinary fragment = compile_fragment(body, optimize);
    auto module = wgsl::emit_wgsl({{&vertex(), "vs_main"}, {&fragment, "fs_main"}}, {});
    INFO((module.ok() ? std::string() : module.error().str()));
    REQUIRE(module.ok());
    Rendered r;
    r.wgsl = module.value().text;
    INFO("WGSL:\n" << r.wgsl);

    auto dawn = shared_dawn_engine();
    REQUIRE(dawn.ok());
    auto messages = dawn.value()->compile(r.wgsl);
    REQUIRE(messages.ok());
    for (const auto& m : messages.value()) FAIL_CHECK(m.type << " " << m.line << ":" << m.column << " " << m.text);
    CHECK(messages.value().empty());

    auto job = test::frame_job<DawnJob>(input(), kSize, kSize, OutputFormat::Rgba16Float, SamplerFilter::Nearest);
    job.wgsl = r.wgsl;
    job.uniform_data = u.bytes();
    job.uses_texture = r.wgsl.find("texture_2d") != std::string::npos;
    r.dawn = test::require_image(dawn.value()->render(job), kSize, kSize);

    auto vk = test::frame_job<RenderJob>(input(), kSize, kSize, OutputFormat::Rgba16Float, SamplerFilter::Nearest);
    vk.vertex_spirv = vertex();
    vk.fragment_spirv = fragment;
    vk.uniform_data = u.bytes();
    r.vulkan = test::require_image(vulkan().render(vk), kSize, kSize);

    float worst = 0;
    for (size_t k = 0; k < r.dawn.rgba.size(); ++k) {
        const float d = r.dawn.rgba[k], v = r.vulkan.rgba[k];
        if (std::isnan(d) && std::isnan(v)) continue;
        worst = std::max(worst, std::isnan(d) || std::isnan(v) ? 1e9f : std::fabs(d - v));
    }
    if (vulkan_agrees) CHECK(worst <= tolerance);
    return r;
}

std::array<float, 4> pixel(const Image& image, int x = kSize / 2, int y = kSize / 2) { return image.pixel(x, y); }

}  // namespace

TEST_CASE("wgsl: GLSL mod() of negatives keeps the divisor's sign, unlike WGSL's %", "[wgsl]") {
    Uniforms u;
    u.a[0] = -7.5f; u.a[1] = 2.0f; u.a[2] = 7.5f; u.a[3] = -2.0f;
    auto r = check_construct(R"(void main() {
        fragColor = vec4(mod(p.a.x, p.a.y), mod(p.a.z, p.a.w), mod(p.a.x, p.a.w), 1.0);
    })", u);
    CHECK_THAT(r.wgsl, Contains("floor("));
    const auto px = pixel(r.dawn);
    CHECK(px[0] == Approx(0.5f));    // WGSL's -7.5 % 2.0 would give -1.5
    CHECK(px[1] == Approx(-0.5f));   // 7.5 % -2.0 would give 1.5
    CHECK(px[2] == Approx(-1.5f));
}

TEST_CASE("wgsl: integer division and remainder of negatives follow SPIR-V", "[wgsl]") {
    Uniforms u;
    u.i[0] = -7; u.i[1] = 2; u.i[2] = 7; u.i[3] = -2;
    // glslang turns GLSL's int % into OpSMod: the remainder takes the DIVISOR's sign (WGSL's %
    // takes the dividend's). Mesa 22.3.6 lavapipe returns the dividend-signed remainder for OpSMod,
    // against the SPIR-V spec, so this case checks the spec's values rather than Vulkan's pixels.
    auto r = check_construct(R"(void main() {
        ivec4 q = ivec4(p.i.x / p.i.y, p.i.z / p.i.w, p.i.x % p.i.y, p.i.z % p.i.w);
        fragColor = vec4(q);
    })", u, true, 2e-3f, /*vulkan_agrees*/ false);
    CHECK_THAT(r.wgsl, Contains("select("));
    const auto px = pixel(r.dawn);
    CHECK(px[0] == -3.0f);  // truncating division
    CHECK(px[1] == -3.0f);
    CHECK(px[2] == 1.0f);   // OpSMod(-7, 2): the divisor's sign
    CHECK(px[3] == -1.0f);  // OpSMod(7, -2)
    CHECK(pixel(r.vulkan)[0] == -3.0f);
    CHECK(pixel(r.vulkan)[1] == -3.0f);
    // What lavapipe gives for the same OpSMod (the dividend's sign): if a Mesa update fixes it,
    // this fails and the vulkan_agrees exception above can go.
    CHECK(pixel(r.vulkan)[2] == -1.0f);
    CHECK(pixel(r.vulkan)[3] == 1.0f);
}

TEST_CASE("wgsl: smoothstep and clamp with reversed constant edges are spelled out", "[wgsl]") {
    Uniforms u;
    auto r = check_construct(R"(void main() {
        float x = vTexCoord.x;
        fragColor = vec4(smoothstep(0.85, 0.4, x), smoothstep(0.4, 0.85, x), clamp(x, 0.75, 0.25), 1.0);
    })", u);
    CHECK_THAT(r.wgsl, !Contains("smoothstep(0.85, 0.4"));  // a WGSL shader-creation error
    CHECK_THAT(r.wgsl, Contains("smoothstep(0.4, 0.85"));    // the ordered one stays a builtin
    CHECK_THAT(r.wgsl, !Contains("clamp(vTexCoord.x, 0.75, 0.25)"));
    // At x = 1/32 the reversed smoothstep is 1 (x below both edges), the ordered one 0.
    CHECK(pixel(r.dawn, 0, 0)[0] == Approx(1.0f));
    CHECK(pixel(r.dawn, 0, 0)[1] == Approx(0.0f));
    CHECK(pixel(r.dawn, 0, 0)[2] == Approx(0.25f));  // min(max(x, 0.75), 0.25)
}

TEST_CASE("wgsl: NaN from the host is detected and compares unordered", "[wgsl]") {
    Uniforms u;
    u.a[0] = std::numeric_limits<float>::quiet_NaN();
    u.a[1] = 1.0f;
    u.a[2] = std::numeric_limits<float>::infinity();
    auto r = check_construct(R"(void main() {
        float n = p.a.x;
        fragColor = vec4(isnan(n) ? 1.0 : 0.0, (n < p.a.y) ? 1.0 : 0.0, (n != n) ? 1.0 : 0.0,
                         isinf(p.a.z) && !isnan(p.a.y) ? 1.0 : 0.0);
    })", u);
    const auto px = pixel(r.dawn);
    CHECK(px[0] == 1.0f);  // isnan by the bits: WGSL may assume no NaN in float maths
    CHECK(px[1] == 0.0f);  // ordered <: false for NaN
    CHECK(px[2] == 1.0f);  // != is unordered: true for NaN
    CHECK(px[3] == 1.0f);
}

TEST_CASE("wgsl: loops with continue, break and loop-carried values", "[wgsl]") {
    Uniforms u;
    u.i[0] = 10;  // trip count
    u.i[1] = 3;   // skipped index
    u.a[0] = 20.0f;  // break once the sum passes this
    auto r = check_construct(R"(void main() {
        float sum = 0.0;
        int last = -1;
        for (int k = 0; k < p.i.x; ++k) {
            if (k == p.i.y) continue;
            if (sum > p.a.x) break;
            sum += float(k) * vTexCoord.x * 2.0;
            last = k;
        }
        int w = 0;
        do { w += 2; } while (w < p.i.y);
        fragColor = vec4(sum, float(last), float(w), 1.0);
    })", u);
    CHECK_THAT(r.wgsl, Contains("loop {"));
    CHECK_THAT(r.wgsl, Contains("continue"));
    CHECK_THAT(r.wgsl, Contains("break"));
    // At the right edge (x = 31/32, step 1.9375 per k): after k = 5 the sum is 23.25 > 20, so k = 6
    // breaks with k = 3 skipped on the way.
    const auto px = pixel(r.dawn, kSize - 1, 0);
    CHECK(px[1] == 5.0f);
    CHECK(px[0] == Approx(23.25f).margin(0.02));
    CHECK(px[2] == 4.0f);
}

TEST_CASE("wgsl: a value built inside a loop and read after it is hoisted out of the loop", "[wgsl][regression]") {
    // The shape Dawn once rejected ("unresolved value"): s is a composite insert inside the loop,
    // and the loop's only exit is the break, so SPIR-V reads the insert's result after the loop
    // directly (no phi). It must live in a function-scope var, with or without the optimiser.
    Uniforms u;
    u.a[0] = 0.25f;
    u.i[0] = 3;  // the loop runs k = 0..3 and leaves with k = 4
    for (bool optimize : {true, false}) {
        INFO("optimised: " << optimize);
        auto r = check_construct(R"(void main() {
            vec4 s = vec4(0.0, 0.0, 0.0, 1.0);
            int k = 0;
            while (true) {
                s.y = float(k) * p.a.x + vTexCoord.x;
                k++;
                if (k > p.i.x) break;
            }
            s.x = float(k) / 8.0;
            fragColor = s;
        })", u, optimize);
        CHECK_THAT(r.wgsl, Contains("loop {"));
        const auto px = pixel(r.dawn, 0, 0);
        CHECK(px[0] == 0.5f);                                  // k = 4 after the loop
        CHECK(px[1] == Approx(3 * 0.25f + 0.5f / kSize));      // the last pass's s.y
    }
}

TEST_CASE("wgsl: early return and discard end their paths", "[wgsl]") {
    Uniforms u;
    auto r = check_construct(R"(void main() {
        if (vTexCoord.x < 0.25) { fragColor = vec4(1.0, 0.0, 0.0, 1.0); return; }
        if (vTexCoord.x > 0.75) discard;
        fragColor = texture(source, vTexCoord);
    })", u);
    CHECK_THAT(r.wgsl, Contains("discard;"));
    CHECK(pixel(r.dawn, 0, 0)[0] == 1.0f);
    CHECK(pixel(r.dawn, kSize - 1, 0)[3] == 0.0f);  // discarded: the clear colour
    // A texture sample after a non-uniform return: WGSL's uniformity rule is turned off, as GLSL never had it.
    CHECK_THAT(r.wgsl, Contains("diagnostic(off, derivative_uniformity)"));
}

TEST_CASE("wgsl: bool to float, select and ternaries with branches", "[wgsl]") {
    Uniforms u;
    u.a[0] = 0.5f;
    auto r = check_construct(R"(
        float expensive(float x) { return sin(x) * 0.5; }
        void main() {
            bool right = vTexCoord.x > p.a.x;
            float f = float(right);
            vec3 c = right ? vec3(0.25) : texture(source, vTexCoord).rgb;
            float g = vTexCoord.y > 0.5 ? expensive(vTexCoord.x) : 0.0;
            fragColor = vec4(f, c.g, g, 1.0);
        })", u);
    CHECK_THAT(r.wgsl, Contains("select("));
    CHECK(pixel(r.dawn, kSize - 1, 0)[0] == 1.0f);
    CHECK(pixel(r.dawn, 0, 0)[0] == 0.0f);
}

TEST_CASE("wgsl: switch, integer bits, shifts and bitcasts", "[wgsl]") {
    Uniforms u;
    u.i[0] = 2;
    u.i[1] = -16;
    auto r = check_construct(R"(void main() {
        float v;
        switch (p.i.x) {
            case 0: v = 0.1; break;
            case 1: case 2: v = 0.2; break;
            default: v = 0.3; break;
        }
        uint bits = floatBitsToUint(vTexCoord.x) >> 16;
        int shifted = p.i.y >> 2;
        fragColor = vec4(v, float(shifted), float(bits & 0xffu) / 255.0, float(uint(p.i.y) >> 28));
    })", u);
    const auto px = pixel(r.dawn);
    CHECK(px[0] == Approx(0.2f).margin(1e-3));  // half-float read-back
    CHECK(px[1] == -4.0f);   // arithmetic shift of a negative int
    CHECK(px[3] == 15.0f);   // logical shift of the same bits as uint
}

TEST_CASE("wgsl: a switch case falling through into a case whose value is a phi", "[wgsl][regression]") {
    // Case 1's block is reached from the switch and from case 0: its phi needs the switch edge's
    // copy too, or case 1 reads the value case 0 left (found by fuzzing the emitter).
    for (int selector : {0, 1, 2}) {
        INFO("selector " << selector);
        Uniforms u;
        u.i[0] = selector;
        u.a[0] = 0.05f;
        auto r = check_construct(R"(void main() {
            float v = p.a.x;
            switch (p.i.x) {
                case 0: v += 0.1;
                case 1: v += 0.2; break;
                default: v = 0.3;
            }
            fragColor = vec4(v, 0.0, 0.0, 1.0);
        })", u);
        const float expected = selector == 0 ? 0.35f : selector == 1 ? 0.25f : 0.3f;
        CHECK(pixel(r.dawn)[0] == Approx(expected).margin(1e-3));
        CHECK(pixel(r.vulkan)[0] == Approx(expected).margin(1e-3));
    }
}

TEST_CASE("wgsl: derivatives, vector shuffles and composite inserts", "[wgsl]") {
    Uniforms u;
    auto r = check_construct(R"(void main() {
        vec4 t = texture(source, vTexCoord);
        vec2 d = vec2(dFdx(vTexCoord.x), dFdy(vTexCoord.y)) * 16.0;
        vec4 s = t.wzyx;
        s.y = d.x;
        s.z = d.y;
        fragColor = vec4(s.xy, s.z, t.x);
    })", u);
    CHECK(pixel(r.dawn)[1] == Approx(1.0f));
    CHECK(pixel(r.dawn)[2] == Approx(1.0f));
}

TEST_CASE("wgsl: modf and frexp write their second part through the pointer, and textureGather keeps its component", "[wgsl]") {
    Uniforms u;
    u.a[0] = -2.75f;
    u.a[1] = 12.5f;
    auto r = check_construct(R"(void main() {
        float whole;
        float f = modf(p.a.x + vTexCoord.x, whole);
        int e;
        float m = frexp(p.a.y * (1.0 + vTexCoord.y), e);
        vec4 g = textureGather(source, vTexCoord, 1) + textureGatherOffset(source, vTexCoord, ivec2(1, 0), 0);
        fragColor = vec4(f + whole * 0.125, m * float(e) * 0.0625, g.x + g.w, g.y - g.z);
    })", u);
    CHECK_THAT(r.wgsl, Contains("modf("));
    CHECK_THAT(r.wgsl, Contains("frexp("));
    CHECK_THAT(r.wgsl, Contains("textureGather(1i, "));
    CHECK_THAT(r.wgsl, Contains("vec2<i32>(1i, 0i))"));
}

TEST_CASE("wgsl: unoptimised glslang output (calls, pointer parameters, locals) translates too", "[wgsl]") {
    Uniforms u;
    u.a[0] = 3.0f;
    auto r = check_construct(R"(
        void scale(inout vec3 c, float k) { c *= k; }
        float twice(float x) { return x * 2.0; }
        void main() {
            vec3 c = texture(source, vTexCoord).rgb;
            scale(c, twice(p.a.x) / 6.0);
            for (int k = 0; k < 3; ++k) c[k] = c[k] + 0.125;
            fragColor = vec4(c, 1.0);
        })", u, /*optimize*/ false);
    CHECK_THAT(r.wgsl, Contains("ptr<function, vec3<f32>>"));
    CHECK_THAT(r.wgsl, Contains("fn twice("));
}

TEST_CASE("wgsl: an instruction outside the subset is an error naming the opcode", "[wgsl][errors]") {
    const SpirvBinary fragment = compile_fragment(R"(void main() {
        uint carry;
        uint sum = uaddCarry(uint(p.i.x), 4000000000u, carry);
        fragColor = vec4(float(sum), float(carry), 0.0, 1.0);
    })", true);
    auto module = wgsl::emit_wgsl({{&vertex(), "vs_main"}, {&fragment, "fs_main"}}, {});
    REQUIRE(!module.ok());
    CHECK(module.error().kind == ErrorKind::Validation);
    CHECK_THAT(module.error().str(), Contains("OpIAddCarry"));
}

TEST_CASE("wgsl: an unsupported construct in a template names the template file and line", "[wgsl][errors]") {
    test::ScratchTemplates scratch;
    std::string glsl = scratch.read("stages/vignette.glsl");
    const std::string marker = "    return color * (1.0 - smoothstep(0.4, 0.85, r));";
    REQUIRE(glsl.find(marker) != std::string::npos);
    glsl.replace(glsl.find(marker), marker.size(),
                 "    uint carry;\n"
                 "    uint total = uaddCarry(uint(r * 4.0e9), 4000000000u, carry);\n"
                 "    return color * float(carry + total % 2u);");
    scratch.write("stages/vignette.glsl", glsl);
    auto lib = scratch.load();
    REQUIRE(lib.ok());
    auto preset = lib.value()->lookup_preset("quiet-frame");
    REQUIRE(preset.ok());
    auto compiled = compile_variant(*lib.value(), *preset.value(), {}, Cache());
    REQUIRE(compiled.ok());
    auto out = emit_target(compiled.value(), TargetId::Wgsl, Cache());
    REQUIRE(!out.ok());
    const std::string message = out.error().str();
    CHECK_THAT(message, Contains("OpIAddCarry"));
    CHECK_THAT(message, Contains("vignette.glsl:"));
    // The line is the uaddCarry line of the template.
    const int expected = 1 + static_cast<int>(std::count(glsl.begin(), glsl.begin() + static_cast<long>(glsl.find("uaddCarry")), '\n'));
    CHECK(out.error().line == expected);
    // The other targets are unaffected: SPIRV-Cross has a GLSL spelling for it.
    CHECK(emit_target(compiled.value(), TargetId::Glsl450, Cache()).ok());
}

TEST_CASE("wgsl: every preset's module declares the documented bindings and the manifest describes them",
          "[wgsl]") {
    const TemplateLibrary& lib = test::shipped_library();
    CompiledVariant c = test::compile_or_fail(lib, "crt-shadow-mask");
    auto out = emit_target(c, TargetId::Wgsl, Cache());
    REQUIRE(out.ok());
    const std::string& text = out.value().files.front().data;
    CHECK_THAT(text, Contains("@group(0) @binding(0) var<uniform> crt: CrtParams;"));
    CHECK_THAT(text, Contains("@group(0) @binding(1) var source: texture_2d<f32>;"));
    CHECK_THAT(text, Contains("@group(0) @binding(2) var source_sampler: sampler;"));
    CHECK_THAT(text, Contains("crt.maskSize"));  // the spec's param names
    CHECK_THAT(text, Contains("@vertex"));
    CHECK_THAT(text, Contains("@fragment"));
    CHECK_THAT(out.value().manifest_json, Contains("\"bindGroupLayout\""));
    CHECK_THAT(out.value().manifest_json, Contains("\"minBindingSize\""));
    // The uniform buffer's WGSL byte layout is the std140 layout the other targets use.
    const auto manifest = nlohmann::json::parse(out.value().manifest_json);
    const auto& members = manifest["uniformBuffer"]["members"];
    const ReflectedBlock& block = c.reflection.uniform_blocks.front();
    REQUIRE(members.size() == block.members.size());
    for (size_t k = 0; k < block.members.size(); ++k) {
        CHECK(members[k]["name"] == block.members[k].name);
        CHECK(members[k]["offset"] == block.members[k].offset);
    }
    CHECK(manifest["uniformBuffer"]["size"].get<uint32_t>() % 16 == 0);
}

TEST_CASE("wgsl: every preset x every uniform selection x precision compiles in Dawn with no message",
          "[wgsl]") {
    const TemplateLibrary& lib = test::shipped_library();
    size_t modules = 0;
    for (const Preset& p : lib.presets()) {
        for (const char* uniforms : {"default", "all", "none"}) {
            for (Precision precision : {Precision::High, Precision::Medium}) {
                VariantOptions options;
                options.uniforms = UniformSelection::parse(uniforms).value();
                options.precision = precision;
                auto compiled = compile_variant(lib, p, options, Cache());
                REQUIRE(compiled.ok());
                auto out = emit_target(compiled.value(), TargetId::Wgsl, Cache());
                INFO(p.name << " --uniforms " << uniforms << " --precision " << precision_name(precision));
                REQUIRE(out.ok());
                auto consumed = consume_output(TargetId::Wgsl, out.value().files.front());
                INFO((consumed.ok() ? std::string() : consumed.error().str()));
                CHECK(consumed.ok());
                ++modules;
            }
        }
    }
    CHECK(modules == lib.presets().size() * 6);
}

TEST_CASE("wgsl: gl_FragCoord becomes @builtin(position) with the same top-left origin", "[wgsl]") {
    Uniforms u;
    auto r = check_construct(R"(void main() {
        fragColor = vec4(gl_FragCoord.xy / 16.0, vTexCoord);
    })", u);
    CHECK_THAT(r.wgsl, Contains("@builtin(position) gl_FragCoord: vec4<f32>"));
    CHECK(pixel(r.dawn, 3, 5)[0] == Approx(3.5f / 16.0f));
    CHECK(pixel(r.dawn, 3, 5)[1] == Approx(5.5f / 16.0f));
    CHECK(pixel(r.dawn, 3, 5)[3] == Approx(5.5f / 16.0f).margin(1e-3));  // row 0 is the top on both
}
