// The OpenGL / OpenGL ES engine on Mesa llvmpipe through EGL surfaceless: the GLSL targets
// compiled and rendered by the real GL driver. The hand-written shaders follow what SPIRV-Cross
// emits for the generator's full-screen triangle (gl_VertexID, vTexCoord, y flipped in the vertex
// shader), so the orientation checked here is the one the generated shaders get.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <variant>
#include <vector>

#include "crtforge/crtforge.hpp"
#include "crtforge/runtime/gl_engine.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

// ---- shaders in the style of the GLSL targets --------------------------------------------------

const char* const kVertex330 = R"(#version 330
#ifdef GL_ARB_shading_language_420pack
#extension GL_ARB_shading_language_420pack : require
#endif

out vec2 vTexCoord;

void main()
{
    vec2 _22 = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    vTexCoord = _22;
    gl_Position = vec4((_22 * 2.0) - vec2(1.0), 0.0, 1.0);
    gl_Position.y = -gl_Position.y;
}
)";

// binding = 1 on purpose: the engine binds by name to unit 0 and must not rely on the layout.
const char* const kPassthrough330 = R"(#version 330
#ifdef GL_ARB_shading_language_420pack
#extension GL_ARB_shading_language_420pack : require
#endif

layout(binding = 1) uniform sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    fragColor = texture(source, vTexCoord);
}
)";

const char* const kVertex450 = R"(#version 450

layout(location = 0) out vec2 vTexCoord;

void main()
{
    vec2 _22 = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    vTexCoord = _22;
    gl_Position = vec4((_22 * 2.0) - vec2(1.0), 0.0, 1.0);
    gl_Position.y = -gl_Position.y;
}
)";

const char* const kPassthrough450 = R"(#version 450

layout(binding = 1) uniform sampler2D source;

layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    fragColor = texture(source, vTexCoord);
}
)";

const char* const kVertexEs300 = R"(#version 300 es

out vec2 vTexCoord;

void main()
{
    vec2 _22 = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    vTexCoord = _22;
    gl_Position = vec4((_22 * 2.0) - vec2(1.0), 0.0, 1.0);
    gl_Position.y = -gl_Position.y;
}
)";

const char* const kPassthroughEs300 = R"(#version 300 es
precision highp float;
precision highp int;

uniform highp sampler2D source;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    fragColor = texture(source, vTexCoord);
}
)";

// Two floats from the uniform block, written straight out.
const char* const kUniform330 = R"(#version 330
#ifdef GL_ARB_shading_language_420pack
#extension GL_ARB_shading_language_420pack : require
#endif

layout(binding = 0, std140) uniform CrtParams
{
    float gain;
    float bias;
} crt;

in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;

void main()
{
    fragColor = vec4(crt.gain, crt.bias, 0.0, 1.0);
}
)";

std::string constant330(const std::string& value) {
    return "#version 330\nin vec2 vTexCoord;\nlayout(location = 0) out vec4 fragColor;\n"
           "void main()\n{\n    fragColor = " + value + ";\n}\n";
}

// ---- fixtures ------------------------------------------------------------------------------------

// One engine per API for the whole file.
GlEngine& engine(GlApi api) {
    static auto core = create_gl_engine(GlApi::DesktopCore);
    static auto es = create_gl_engine(GlApi::Es);
    auto& created = api == GlApi::DesktopCore ? core : es;
    INFO((created.ok() ? std::string() : created.error().str()));
    REQUIRE(created.ok());
    return *created.value();
}

GlRenderJob make_job(const std::string& vertex, const std::string& fragment, Image input, int width, int height,
                     OutputFormat format, SamplerFilter filter = SamplerFilter::Nearest) {
    auto job = test::frame_job<GlRenderJob>(std::move(input), width, height, format, filter);
    job.vertex_source = vertex;
    job.fragment_source = fragment;
    return job;
}

Image render_ok(GlApi api, const GlRenderJob& job) {
    return test::require_image(engine(api).render(job), job.width, job.height);
}

Diagnostic render_error(GlApi api, const GlRenderJob& job) {
    auto image = engine(api).render(job);
    REQUIRE_FALSE(image.ok());
    const Diagnostic& error = image.error();
    CHECK(error.str().find('\n') == std::string::npos);  // one line
    return error;
}

// Values every format carries exactly: multiples of 1/64 (halves), HDR and negative ones too.
Image exact_pattern(int width, int height) {
    Image image = Image::make(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            image.set_pixel(x, y, {static_cast<float>(x) / 64.0f, static_cast<float>(y) / 32.0f,
                                   static_cast<float>((x * 7 + y * 3) % 17) * 0.25f - 1.0f, 1.0f - static_cast<float>(x % 3) / 8.0f});
        }
    }
    return image;
}

float max_difference(const Image& a, const Image& b) {
    REQUIRE(a.rgba.size() == b.rgba.size());
    float worst = 0.0f;
    for (size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::fabs(a.rgba[i] - b.rgba[i]));
    return worst;
}

// top-left red, top-right green, bottom-left blue, bottom-right white
Image quadrants() {
    Image image = Image::make(2, 2);
    image.set_pixel(0, 0, {1, 0, 0, 1});
    image.set_pixel(1, 0, {0, 1, 0, 1});
    image.set_pixel(0, 1, {0, 0, 1, 1});
    image.set_pixel(1, 1, {1, 1, 1, 1});
    return image;
}

void check_quadrants(const Image& out) {
    const int w = out.width, h = out.height;
    using P = std::array<float, 4>;
    CHECK(out.pixel(0, 0) == P{1, 0, 0, 1});
    CHECK(out.pixel(w - 1, 0) == P{0, 1, 0, 1});
    CHECK(out.pixel(0, h - 1) == P{0, 0, 1, 1});
    CHECK(out.pixel(w - 1, h - 1) == P{1, 1, 1, 1});
}

std::vector<uint8_t> floats_as_bytes(std::initializer_list<float> values) {
    std::vector<uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.begin(), bytes.size());
    return bytes;
}

}  // namespace

TEST_CASE("the desktop context is OpenGL 4.5 core on llvmpipe, the ES one OpenGL ES 3", "[gl]") {
    const std::string core = engine(GlApi::DesktopCore).renderer();
    const std::string es = engine(GlApi::Es).renderer();
    WARN("desktop: " << core);
    WARN("es: " << es);
    CHECK_THAT(core, Contains("llvmpipe"));
    CHECK_THAT(core, Contains("4.5") && Contains("Core Profile"));
    CHECK_THAT(es, Contains("llvmpipe"));
    CHECK_THAT(es, Contains("OpenGL ES 3."));
}

TEST_CASE("a GLSL 330 passthrough reproduces the input exactly", "[gl]") {
    const Image input = exact_pattern(13, 7);
    const Image out = render_ok(GlApi::DesktopCore,
                                make_job(kVertex330, kPassthrough330, input, 13, 7, OutputFormat::Rgba16Float));
    CHECK(out.rgba == input.rgba);
}

TEST_CASE("a GLSL 450 passthrough reproduces the input exactly", "[gl]") {
    const Image input = exact_pattern(9, 11);
    const Image out = render_ok(GlApi::DesktopCore,
                                make_job(kVertex450, kPassthrough450, input, 9, 11, OutputFormat::Rgba16Float));
    CHECK(out.rgba == input.rgba);
}

TEST_CASE("a GLSL ES 300 passthrough reproduces the input exactly on the ES context", "[gl]") {
    const Image input = exact_pattern(10, 6);
    const Image out =
        render_ok(GlApi::Es, make_job(kVertexEs300, kPassthroughEs300, input, 10, 6, OutputFormat::Rgba16Float));
    CHECK(out.rgba == input.rgba);
    // ES sources are also accepted by the desktop core context (ARB_ES3_compatibility).
    const Image desktop = render_ok(
        GlApi::DesktopCore, make_job(kVertexEs300, kPassthroughEs300, input, 10, 6, OutputFormat::Rgba16Float));
    CHECK(desktop.rgba == input.rgba);
}

TEST_CASE("the top row of the input stays the top row of the output", "[gl]") {
    SECTION("desktop, GLSL 330, 8-bit") {
        check_quadrants(render_ok(GlApi::DesktopCore,
                                  make_job(kVertex330, kPassthrough330, quadrants(), 2, 2, OutputFormat::Rgba8Unorm)));
    }
    SECTION("desktop, GLSL 330, magnified 4x") {
        check_quadrants(render_ok(GlApi::DesktopCore,
                                  make_job(kVertex330, kPassthrough330, quadrants(), 8, 8, OutputFormat::Rgba16Float)));
    }
    SECTION("ES, GLSL ES 300") {
        check_quadrants(render_ok(GlApi::Es, make_job(kVertexEs300, kPassthroughEs300, quadrants(), 6, 4,
                                                      OutputFormat::Rgba16Float)));
    }
    SECTION("a red top row and a blue bottom row") {
        Image input = Image::make(5, 3, {0, 0, 0, 1});
        for (int x = 0; x < 5; ++x) {
            input.set_pixel(x, 0, {1, 0, 0, 1});
            input.set_pixel(x, 2, {0, 0, 1, 1});
        }
        const Image out = render_ok(GlApi::DesktopCore,
                                    make_job(kVertex330, kPassthrough330, input, 5, 3, OutputFormat::Rgba8Unorm));
        for (int x = 0; x < 5; ++x) {
            CHECK(out.pixel(x, 0) == std::array<float, 4>{1, 0, 0, 1});
            CHECK(out.pixel(x, 2) == std::array<float, 4>{0, 0, 1, 1});
        }
    }
}

TEST_CASE("the GL engine agrees with the Vulkan engine on orientation", "[gl]") {
    // The same passthrough compiled to SPIR-V for Vulkan (no y flip: Vulkan's y points down).
    CompileOptions options;
    options.language = SourceLanguage::Glsl;
    options.optimize = false;
    options.stage = ShaderStage::Vertex;
    auto vertex = compile_to_spirv(R"(#version 450
layout(location = 0) out vec2 vTexCoord;
void main() {
    vec2 uv = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    vTexCoord = uv;
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
)", options);
    options.stage = ShaderStage::Fragment;
    auto fragment = compile_to_spirv(R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() { fragColor = texture(source, vTexCoord); }
)", options);
    REQUIRE(vertex.ok());
    REQUIRE(fragment.ok());
    auto vulkan = create_vulkan_engine({});
    INFO((vulkan.ok() ? std::string() : vulkan.error().str()));
    REQUIRE(vulkan.ok());
    RenderJob job;
    job.vertex_spirv = vertex.value();
    job.fragment_spirv = fragment.value();
    job.input = quadrants();
    job.filter = SamplerFilter::Nearest;
    job.width = 4;
    job.height = 4;
    job.format = OutputFormat::Rgba8Unorm;
    auto reference = vulkan.value()->render(job);
    REQUIRE(reference.ok());
    const Image out = render_ok(GlApi::DesktopCore,
                                make_job(kVertex330, kPassthrough330, quadrants(), 4, 4, OutputFormat::Rgba8Unorm));
    CHECK(out.rgba == reference.value().rgba);
}

TEST_CASE("uniform block floats reach the shader", "[gl]") {
    GlRenderJob job = make_job(kVertex330, kUniform330, Image(), 3, 2, OutputFormat::Rgba16Float);
    // 8 bytes: the block's two floats. GL sizes the std140 block 16 (rounded up to a vec4); the
    // engine zero-fills that tail, as SPIR-V reflection ends the block at its last member.
    job.uniform_data = floats_as_bytes({0.75f, -2.5f});
    const Image out = render_ok(GlApi::DesktopCore, job);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 3; ++x) CHECK(out.pixel(x, y) == std::array<float, 4>{0.75f, -2.5f, 0.0f, 1.0f});
    }
    SECTION("the same through the ES context") {
        std::string es = kUniform330;
        es.replace(0, es.find("layout(binding"), "#version 300 es\nprecision highp float;\n");
        es.replace(es.find("binding = 0, "), 13, "");
        job.vertex_source = kVertexEs300;
        job.fragment_source = es;
        const Image es_out = render_ok(GlApi::Es, job);
        CHECK(es_out.pixel(1, 1) == std::array<float, 4>{0.75f, -2.5f, 0.0f, 1.0f});
    }
}

TEST_CASE("linear filtering interpolates between texels", "[gl]") {
    Image input = Image::make(2, 1);
    input.set_pixel(0, 0, {0, 0, 0, 1});
    input.set_pixel(1, 0, {1, 1, 1, 1});
    // Output centres at u = 1/8, 3/8, 5/8, 7/8 -> texel coordinates 0.25 .. 1.75: clamp, 1/4, 3/4, clamp.
    const float expected[] = {0.0f, 0.25f, 0.75f, 1.0f};
    for (GlApi api : {GlApi::DesktopCore, GlApi::Es}) {
        const bool es = api == GlApi::Es;
        const Image out = render_ok(api, make_job(es ? kVertexEs300 : kVertex330, es ? kPassthroughEs300 : kPassthrough330,
                                                  input, 4, 1, OutputFormat::Rgba16Float, SamplerFilter::Linear));
        for (int x = 0; x < 4; ++x) CHECK(out.pixel(x, 0)[0] == Approx(expected[x]).margin(1.0 / 256));
    }
}

TEST_CASE("output formats read back as the Vulkan engine's do", "[gl]") {
    for (GlApi api : {GlApi::DesktopCore, GlApi::Es}) {
        const std::string fragment = api == GlApi::Es
                                         ? "#version 300 es\nprecision highp float;\nlayout(location = 0) out vec4 fragColor;\n"
                                           "void main() { fragColor = vec4(0.2, 0.5, 2.5, 0.6); }\n"
                                         : constant330("vec4(0.2, 0.5, 2.5, 0.6)");
        const std::string vertex = api == GlApi::Es ? kVertexEs300 : kVertex330;
        const Image unorm = render_ok(api, make_job(vertex, fragment, Image(), 2, 2, OutputFormat::Rgba8Unorm));
        CHECK(unorm.pixel(1, 1)[0] == 51.0f / 255.0f);
        CHECK(unorm.pixel(1, 1)[1] == 128.0f / 255.0f);
        CHECK(unorm.pixel(1, 1)[2] == 1.0f);  // clamped
        const Image half = render_ok(api, make_job(vertex, fragment, Image(), 2, 2, OutputFormat::Rgba16Float));
        CHECK(half.pixel(0, 0)[2] == 2.5f);  // HDR survives
        CHECK(half.pixel(0, 0)[0] == Approx(0.2).margin(1e-3));
        // sRGB: encoded on store, decoded on readback: the written value on the sRGB byte grid
        // (0.2 stored linear as 51 would decode to 0.033; 0.2 read back raw would be 0.486).
        const Image srgb = render_ok(api, make_job(vertex, fragment, Image(), 2, 2, OutputFormat::Rgba8Srgb));
        CHECK(srgb.pixel(0, 1)[0] == Approx(0.2).margin(0.003));
        CHECK(srgb.pixel(0, 1)[1] == Approx(0.5).margin(0.004));
        CHECK(srgb.pixel(0, 1)[3] == 153.0f / 255.0f);  // alpha stays linear
    }
}

TEST_CASE("a shader the driver rejects is a one-line validation error", "[gl]") {
    SECTION("fragment syntax error") {
        const std::string broken = constant330("vec4(1.0, 0.0, 0.0, 1.0") ;  // missing ')'
        const Diagnostic error = render_error(
            GlApi::DesktopCore, make_job(kVertex330, broken, Image(), 4, 4, OutputFormat::Rgba8Unorm));
        INFO(error.str());
        CHECK(error.kind == ErrorKind::Validation);
        CHECK_THAT(error.message, StartsWith("GL driver rejected the fragment shader: "));
        CHECK(error.message.size() > std::string("GL driver rejected the fragment shader: ").size());
    }
    SECTION("vertex error") {
        std::string broken = kVertex330;
        broken.replace(broken.find("vTexCoord = _22;"), 16, "vTexCoord = undeclared;");
        const Diagnostic error = render_error(
            GlApi::DesktopCore, make_job(broken, kPassthrough330, Image(), 4, 4, OutputFormat::Rgba8Unorm));
        CHECK(error.kind == ErrorKind::Validation);
        CHECK_THAT(error.message, StartsWith("GL driver rejected the vertex shader: "));
        CHECK_THAT(error.message, Contains("undeclared"));
    }
    SECTION("desktop GLSL 450 on the ES context") {
        const Diagnostic error = render_error(
            GlApi::Es, make_job(kVertex450, kPassthrough450, Image(), 4, 4, OutputFormat::Rgba8Unorm));
        CHECK(error.kind == ErrorKind::Validation);
        CHECK_THAT(error.message, StartsWith("GL driver rejected the vertex shader: "));
    }
    SECTION("stages that do not link") {
        std::string fragment = kPassthrough330;
        fragment.replace(fragment.find("in vec2 vTexCoord;"), 18, "in vec3 vTexCoord;");
        fragment.replace(fragment.find("texture(source, vTexCoord)"), 26, "texture(source, vTexCoord.xy)");
        const Diagnostic error = render_error(
            GlApi::DesktopCore, make_job(kVertex330, fragment, Image(), 4, 4, OutputFormat::Rgba8Unorm));
        CHECK(error.kind == ErrorKind::Validation);
        CHECK_THAT(error.message, StartsWith("GL driver rejected the program at link: "));
    }
    // The engine is still usable afterwards.
    render_ok(GlApi::DesktopCore, make_job(kVertex330, kPassthrough330, quadrants(), 2, 2, OutputFormat::Rgba8Unorm));
}

TEST_CASE("bad GL jobs are errors, not crashes", "[gl]") {
    const GlRenderJob good = make_job(kVertex330, kPassthrough330, quadrants(), 4, 4, OutputFormat::Rgba8Unorm);
    auto expect = [&](GlRenderJob job, const std::string& field) {
        const Diagnostic error = render_error(GlApi::DesktopCore, job);
        INFO(error.str());
        CHECK(error.kind == ErrorKind::Input);
        CHECK(error.field == field);
    };
    SECTION("zero size") {
        GlRenderJob job = good;
        job.width = 0;
        expect(job, "job.width");
        job = good;
        job.height = -3;
        expect(job, "job.height");
    }
    SECTION("over GL_MAX_TEXTURE_SIZE") {
        GlRenderJob job = good;
        job.width = 1 << 20;
        expect(job, "job.width");
    }
    SECTION("empty sources") {
        GlRenderJob job = good;
        job.vertex_source.clear();
        expect(job, "job.vertex_source");
        job = good;
        job.fragment_source.clear();
        expect(job, "job.fragment_source");
    }
    SECTION("malformed input image") {
        GlRenderJob job = good;
        Image short_input = *job.input;
        short_input.rgba.resize(3);
        job.input = std::move(short_input);
        expect(job, "job.input");
    }
    SECTION("uniform data shorter than the block") {
        GlRenderJob job = make_job(kVertex330, kUniform330, Image(), 2, 2, OutputFormat::Rgba8Unorm);
        job.uniform_data = floats_as_bytes({0.5f});  // 4 of the 8 bytes its members use
        expect(job, "job.uniform_data");
        job.uniform_data.clear();
        expect(job, "job.uniform_data");
    }
    SECTION("a uniform block the job does not name") {
        GlRenderJob job = make_job(kVertex330, kUniform330, Image(), 2, 2, OutputFormat::Rgba8Unorm);
        job.uniform_data = floats_as_bytes({0.5f, 0.5f, 0.0f, 0.0f});
        job.uniform_block = "Other";
        expect(job, "job.uniform_block");
    }
    render_ok(GlApi::DesktopCore, good);  // and the engine carries on
}

namespace {

// The std140 bytes of the variant's block, filled from the reflection: outputSize = the output,
// sourceSize = the input, time = 0, every other member its value in the variant.
std::vector<uint8_t> uniform_bytes(const CompiledVariant& compiled, int width, int height, int source_width,
                                   int source_height) {
    REQUIRE(compiled.reflection.uniform_blocks.size() == 1);
    const ReflectedBlock& block = compiled.reflection.uniform_blocks[0];
    std::vector<uint8_t> bytes(block.size, 0);
    auto put = [&](uint32_t offset, std::vector<float> values) {
        REQUIRE(offset + values.size() * sizeof(float) <= bytes.size());
        std::memcpy(bytes.data() + offset, values.data(), values.size() * sizeof(float));
    };
    for (const ReflectedMember& member : block.members) {
        if (member.name == "outputSize") {
            put(member.offset, {static_cast<float>(width), static_cast<float>(height)});
        } else if (member.name == "sourceSize") {
            put(member.offset, {static_cast<float>(source_width), static_cast<float>(source_height)});
        } else if (member.name == "time") {
            put(member.offset, {0.0f});
        } else {
            const VariantParam* param = nullptr;
            for (const VariantParam& p : compiled.variant.params) {
                if (p.spec && p.spec->name == member.name) param = &p;
            }
            INFO(member.name);
            REQUIRE(param != nullptr);
            if (const auto* number = std::get_if<double>(&param->value)) {
                put(member.offset, {static_cast<float>(*number)});
            } else if (const auto* color = std::get_if<Color>(&param->value)) {
                put(member.offset, {static_cast<float>((*color)[0]), static_cast<float>((*color)[1]),
                                    static_cast<float>((*color)[2])});
            } else {
                FAIL("member " << member.name << " is not a float or colour param");
            }
        }
    }
    return bytes;
}

}  // namespace

TEST_CASE("the generated GLSL 330 renders in GL as its SPIR-V does in Vulkan", "[gl]") {
    auto lib = TemplateLibrary::load(std::string(CRTFORGE_SOURCE_DIR) + "/templates");
    INFO((lib.ok() ? std::string() : lib.error().str()));
    REQUIRE(lib.ok());
    const Preset* preset = lib.value()->find_preset("crt-shadow-mask");
    REQUIRE(preset != nullptr);
    auto compiled = compile_variant(*lib.value(), *preset, {}, Cache());
    INFO((compiled.ok() ? std::string() : compiled.error().str()));
    REQUIRE(compiled.ok());
    auto glsl = emit_target(compiled.value(), TargetId::Glsl330, Cache());
    INFO((glsl.ok() ? std::string() : glsl.error().str()));
    REQUIRE(glsl.ok());
    REQUIRE(glsl.value().files.size() == 2);  // vertex first, then fragment

    const int width = 64, height = 48;
    const Image input = Image::make(width, height, {0.5f, 0.5f, 0.5f, 1.0f});
    const std::vector<uint8_t> uniforms = uniform_bytes(compiled.value(), width, height, width, height);

    auto vulkan = create_vulkan_engine({});
    INFO((vulkan.ok() ? std::string() : vulkan.error().str()));
    REQUIRE(vulkan.ok());
    auto render_vulkan = [&](OutputFormat format) {
        RenderJob job;
        job.vertex_spirv = compiled.value().vertex;
        job.fragment_spirv = compiled.value().fragment;
        job.input = input;
        job.filter = SamplerFilter::Linear;
        job.width = width;
        job.height = height;
        job.format = format;
        job.uniform_data = uniforms;
        job.uniform_binding = compiled.value().reflection.uniform_blocks[0].binding;
        REQUIRE(compiled.value().reflection.textures.size() == 1);
        job.texture_binding = compiled.value().reflection.textures[0].binding;
        auto image = vulkan.value()->render(job);
        INFO((image.ok() ? std::string() : image.error().str()));
        REQUIRE(image.ok());
        return std::move(image).value();
    };
    auto render_gl = [&](GlApi api, const TargetOutput& target, OutputFormat format) {
        REQUIRE(target.files.size() == 2);  // vertex first, then fragment
        GlRenderJob job = make_job(target.files[0].data, target.files[1].data, input, width, height, format,
                                   SamplerFilter::Linear);
        job.uniform_data = uniforms;
        return render_ok(api, job);
    };

    const Image reference = render_vulkan(OutputFormat::Rgba8Unorm);
    const Image gl_image = render_gl(GlApi::DesktopCore, glsl.value(), OutputFormat::Rgba8Unorm);
    const float difference = max_difference(gl_image, reference);
    WARN("crt-shadow-mask 64x48, GL (GLSL 330) vs Vulkan (SPIR-V), Rgba8Unorm: max difference "
         << difference * 255.0f << "/255");
    CHECK(difference <= 2.0f / 255.0f + 1e-6f);
    // Not trivially equal: the effect really ran (the mask and vignette darken some pixels).
    CHECK(*std::min_element(gl_image.rgba.begin(), gl_image.rgba.end()) < 0.4f);

    // Before 8-bit quantisation: the two driver compilers' float results.
    const float float_difference = max_difference(render_gl(GlApi::DesktopCore, glsl.value(), OutputFormat::Rgba16Float),
                                                  render_vulkan(OutputFormat::Rgba16Float));
    WARN("... the same at Rgba16Float: max difference " << float_difference << " (" << float_difference * 255.0f
                                                         << "/255)");
    CHECK(float_difference <= 2.0f / 255.0f);

    // GLSL ES 300 on the ES context, GLSL 450 on the desktop one.
    for (TargetId target : {TargetId::GlslEs300, TargetId::Glsl450}) {
        auto emitted = emit_target(compiled.value(), target, Cache());
        INFO((emitted.ok() ? std::string() : emitted.error().str()));
        REQUIRE(emitted.ok());
        const GlApi api = target == TargetId::GlslEs300 ? GlApi::Es : GlApi::DesktopCore;
        const float target_difference = max_difference(render_gl(api, emitted.value(), OutputFormat::Rgba8Unorm), reference);
        WARN("... " << target_info(target).name << " vs Vulkan, Rgba8Unorm: max difference " << target_difference * 255.0f
                    << "/255");
        CHECK(target_difference <= 2.0f / 255.0f + 1e-6f);
    }
}

// ---- several textures, wrap modes, viewport and clear colour -------------------------------------

namespace {

using P = std::array<float, 4>;

// A GLSL 330 fragment shader around `body` (which writes fragColor) with `declarations` before it.
std::string fragment330(const std::string& declarations, const std::string& body) {
    return "#version 330\n" + declarations + "\nin vec2 vTexCoord;\nlayout(location = 0) out vec4 fragColor;\n"
           "void main()\n{\n" + body + "\n}\n";
}

// A width x 1 image whose red channel holds `values` (the other channels 0, alpha 1).
Image row_of(std::initializer_list<float> values) {
    Image image = Image::make(static_cast<int>(values.size()), 1);
    int x = 0;
    for (float v : values) image.set_pixel(x++, 0, {v, 0.0f, 0.0f, 1.0f});
    return image;
}

TextureInput texture_input(std::string name, Image image, SamplerFilter filter, WrapMode wrap = WrapMode::ClampToEdge) {
    TextureInput texture;
    texture.name = std::move(name);
    texture.image = std::move(image);
    texture.filter = filter;
    texture.wrap = wrap;
    return texture;
}

}  // namespace

TEST_CASE("extra textures are bound by name with their own filters", "[gl]") {
    // Bindings in the source that differ from the units the engine picks: it binds by name.
    const std::string shader = fragment330(
        "uniform sampler2D source;\nuniform sampler2D texA;\nuniform sampler2D texB;",
        "    fragColor = vec4(texture(texA, vTexCoord).r, texture(texB, vTexCoord).r,\n"
        "                     texture(source, vTexCoord).r, 1.0);");
    // Two output columns sample u = 1/4 and 3/4: the centres of texA's two texels (nearest), and
    // exactly halfway between texB's texels 0|1 and 2|3 (linear: their averages).
    for (GlApi api : {GlApi::DesktopCore, GlApi::Es}) {
        INFO((api == GlApi::Es ? "ES" : "desktop"));
        std::string fragment = shader;
        if (api == GlApi::Es) fragment.replace(0, 13, "#version 300 es\nprecision highp float;\n");
        GlRenderJob job = make_job(api == GlApi::Es ? kVertexEs300 : kVertex330, fragment,
                                   Image::make(1, 1, {0.125f, 0, 0, 1}), 2, 2, OutputFormat::Rgba16Float);
        job.textures.push_back(texture_input("texA", row_of({0.25f, 0.75f}), SamplerFilter::Nearest));
        job.textures.push_back(texture_input("texB", row_of({0.0f, 1.0f, 0.5f, 0.25f}), SamplerFilter::Linear));
        const Image out = render_ok(api, job);
        for (int y = 0; y < 2; ++y) {
            INFO("row " << y);
            CHECK(out.pixel(0, y)[0] == 0.25f);
            CHECK(out.pixel(1, y)[0] == 0.75f);
            CHECK(out.pixel(0, y)[1] == Approx(0.5).margin(1.0 / 256));
            CHECK(out.pixel(1, y)[1] == Approx(0.375).margin(1.0 / 256));
            CHECK(out.pixel(0, y)[2] == 0.125f);  // the input is still on unit 0
            CHECK(out.pixel(1, y)[2] == 0.125f);
        }
    }
}

TEST_CASE("each GL wrap mode returns its texel outside 0..1, for the input and an extra texture", "[gl]") {
    // Column 0 samples u = -0.375, column 1 u = 1.375: the centres of texels -2 and 5 of a 4-texel
    // row (texel centres, not the edges at -0.25 / 1.25, where nearest may round either way).
    const std::string shader =
        fragment330("uniform sampler2D source;\nuniform sampler2D extra;",
                    "    vec2 uv = vec2(vTexCoord.x < 0.5 ? -0.375 : 1.375, 0.5);\n"
                    "    fragColor = vec4(texture(source, uv).r, texture(extra, uv).r, 0.0, 1.0);");
    const Image texels = row_of({0.125f, 0.25f, 0.5f, 1.0f});
    struct Case {
        WrapMode wrap;
        float left, right;
    };
    const Case cases[] = {{WrapMode::ClampToEdge, 0.125f, 1.0f},     // texel 0 / texel 3
                          {WrapMode::Repeat, 0.5f, 0.25f},           // -2 -> 2, 5 -> 1
                          {WrapMode::MirroredRepeat, 0.25f, 0.5f}};  // -2 -> 1, 5 -> 2
    GlRenderJob job = make_job(kVertex330, shader, texels, 2, 1, OutputFormat::Rgba16Float);
    for (const Case& c : cases) {
        INFO("wrap mode " << static_cast<int>(c.wrap));
        job.wrap = c.wrap;
        job.textures = {texture_input("extra", texels, SamplerFilter::Nearest, c.wrap)};
        const Image out = render_ok(GlApi::DesktopCore, job);
        CHECK(out.pixel(0, 0) == P{c.left, c.left, 0.0f, 1.0f});
        CHECK(out.pixel(1, 0) == P{c.right, c.right, 0.0f, 1.0f});
    }
}

TEST_CASE("a GL viewport draws a pasted full render and keeps the clear colour around it", "[gl]") {
    const std::string shader =
        fragment330("uniform sampler2D source;", "    fragColor = vec4(texture(source, vTexCoord).rg, vTexCoord);");
    Image input = Image::make(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) input.set_pixel(x, y, {(x + 1) / 8.0f, (y + 1) / 4.0f, 0.0f, 1.0f});
    for (GlApi api : {GlApi::DesktopCore, GlApi::Es}) {
        INFO((api == GlApi::Es ? "ES" : "desktop"));
        GlRenderJob job = make_job(kVertex330, shader, input, 8, 4, OutputFormat::Rgba16Float);
        if (api == GlApi::Es) {
            job.vertex_source = kVertexEs300;
            job.fragment_source.replace(0, 13, "#version 300 es\nprecision highp float;\n");
        }
        const Image full = render_ok(api, job);
        job.width = 16;
        job.height = 8;
        job.viewport = {4, 2, 8, 4};
        job.clear_color = {0, 0, 0, 1};
        const Image out = render_ok(api, job);
        for (int y = 0; y < 8; ++y) {
            for (int x = 0; x < 16; ++x) {
                INFO("pixel " << x << ", " << y);
                const bool inside = x >= 4 && x < 12 && y >= 2 && y < 6;
                CHECK(out.pixel(x, y) == (inside ? full.pixel(x - 4, y - 2) : P{0, 0, 0, 1}));
            }
        }
        CHECK(out.pixel(4, 2)[0] == input.pixel(0, 0)[0]);  // the viewport's top-left is the input's
        CHECK(out.pixel(4, 2)[1] == input.pixel(0, 0)[1]);
        // The clear colour is linear like the shader's output: an sRGB target stores it encoded.
        job.format = OutputFormat::Rgba8Srgb;
        job.clear_color = {0.5f, 0.25f, 0.0f, 1.0f};
        const Image srgb = render_ok(api, job);
        CHECK(srgb.pixel(15, 7)[0] == Approx(0.5).margin(0.004));
        CHECK(srgb.pixel(15, 7)[1] == Approx(0.25).margin(0.004));
    }
}

TEST_CASE("bad GL textures, viewports and clear colours are input errors", "[gl]") {
    const std::string shader = fragment330("uniform sampler2D source;\nuniform sampler2D lut;",
                                           "    fragColor = texture(source, vTexCoord) + texture(lut, vTexCoord);");
    GlRenderJob good =
        make_job(kVertex330, shader, Image::make(2, 2, {0.25f, 0, 0, 1}), 16, 8, OutputFormat::Rgba16Float);
    good.textures = {texture_input("lut", Image::make(2, 1, {0.5f, 0, 0, 0}), SamplerFilter::Linear)};
    auto expect = [](const GlRenderJob& job, const std::string& field) {
        const Diagnostic error = render_error(GlApi::DesktopCore, job);
        INFO(error.str());
        CHECK(error.kind == ErrorKind::Input);
        CHECK(error.field == field);
    };
    GlRenderJob job = good;
    job.viewport = {4, 6, 8, 4};  // 6 + 4 > 8
    expect(job, "job.viewport");
    job.viewport = {4, 2, 8, 0};  // a zero side
    expect(job, "job.viewport");
    job.viewport = {0, -2, 4, 4};
    expect(job, "job.viewport");

    job = good;
    job.textures[0].name.clear();
    expect(job, "job.textures[0].name");
    job = good;
    job.textures.push_back(texture_input("lut", Image{}, SamplerFilter::Nearest));  // one name, two textures
    expect(job, "job.textures[1].name");
    job = good;
    job.textures[0].name = "source";  // the input's sampler
    expect(job, "job.textures[0].name");

    job = good;
    {
        Image broken = *job.textures[0].image;
        broken.rgba.resize(3);
        job.textures[0].image = std::move(broken);
    }
    expect(job, "job.textures[0].image");
    job.textures[0].image = Image::make(kMaxImageDimension + 1, 1);
    expect(job, "job.textures[0].image");

    job = good;
    job.clear_color[0] = std::nanf("");
    expect(job, "job.clear_color");

    const Image out = render_ok(GlApi::DesktopCore, good);  // the engine carries on
    CHECK(out.pixel(0, 0)[0] == 0.75f);
}

TEST_CASE("plain uniforms are set by name, and one the job leaves unset is an error", "[gl][webgl2]") {
    const std::string fragment = R"(#version 300 es
precision highp float;
uniform float gain;
uniform vec3 tint;
uniform int steps;
in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
void main() { fragColor = vec4(tint * gain, float(steps)); }
)";
    GlRenderJob job = make_job(kVertexEs300, fragment, Image(), 3, 2, OutputFormat::Rgba16Float);
    job.uniform_data.clear();
    PlainUniform gain{PlainUniform::Kind::Float, "gain", 1, {0.5f}, {}};
    PlainUniform tint{PlainUniform::Kind::Float, "tint", 3, {1.0f, -2.0f, 0.25f}, {}};
    PlainUniform steps{PlainUniform::Kind::Int, "steps", 1, {}, {3}};
    PlainUniform unused{PlainUniform::Kind::Float, "notInTheShader", 2, {9.0f, 9.0f}, {}};  // skipped
    job.plain_uniforms = {gain, tint, steps, unused};
    const Image out = render_ok(GlApi::Es, job);
    CHECK(out.pixel(2, 1) == std::array<float, 4>{0.5f, -1.0f, 0.125f, 3.0f});

    job.plain_uniforms = {gain, steps};
    const Diagnostic missing = render_error(GlApi::Es, job);
    CHECK_THAT(missing.str(), Contains("the shader's uniform 'tint' is not among the job's plain uniforms"));
}
