// The headless Vulkan engine on Mesa lavapipe, with the validation layer on: every render here
// must come back with no validation message (the engine turns any into an error).
#include <catch2/catch.hpp>

#include <climits>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "crtforge/runtime/render_engine.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "runtime/vulkan/vulkan_context.hpp"
#include "runtime/vulkan/vulkan_memory_pool.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
using Catch::Matchers::Contains;

// The generator's full-screen triangle: uv (0,0) is the top-left of the input and of the output.
const char* const kVertexShader = R"(#version 450
layout(location = 0) out vec2 vTexCoord;
void main() {
    vec2 uv = vec2(float((gl_VertexIndex << 1) & 2), float(gl_VertexIndex & 2));
    vTexCoord = uv;
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* const kPassthrough = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() { fragColor = texture(source, vTexCoord); }
)";

// Writes a constant, to test what the output format does to a known value.
std::string constant_shader(const std::string& value) {
    return "#version 450\n"
           "layout(location = 0) in vec2 vTexCoord;\n"
           "layout(location = 0) out vec4 fragColor;\n"
           "void main() { fragColor = " + value + "; }\n";
}

const char* const kUniformShader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 0, binding = 0) uniform CrtParams { float a; float b; } u;
void main() { fragColor = vec4(u.a, u.b, 0.0, 1.0); }
)";

SpirvBinary compile(const std::string& source, ShaderStage stage) {
    CompileOptions options;
    options.stage = stage;
    options.language = SourceLanguage::Glsl;
    options.optimize = false;  // keep the module as written: these tests are about the engine
    auto spirv = compile_to_spirv(source, options);
    INFO((spirv.ok() ? std::string() : spirv.error().str()));
    REQUIRE(spirv.ok());
    return spirv.value();
}

const SpirvBinary& vertex_spirv() {
    static const SpirvBinary spirv = compile(kVertexShader, ShaderStage::Vertex);
    return spirv;
}

// One engine for the whole file: creating an instance with validation costs tens of milliseconds.
RenderEngine& engine() {
    static auto created = create_vulkan_engine(EngineOptions{"", /*validation*/ true});
    INFO((created.ok() ? std::string() : created.error().str()));
    REQUIRE(created.ok());
    return *created.value();
}

RenderJob make_job(const std::string& fragment, Image input, int width, int height, OutputFormat format,
                   SamplerFilter filter = SamplerFilter::Nearest) {
    auto job = test::frame_job<RenderJob>(std::move(input), width, height, format, filter);
    job.vertex_spirv = vertex_spirv();
    job.fragment_spirv = compile(fragment, ShaderStage::Fragment);
    return job;
}

Image render_ok(const RenderJob& job) {
    return test::require_image(engine().render(job), job.width, job.height);
}

std::string render_error(const RenderJob& job) {
    auto image = engine().render(job);
    REQUIRE_FALSE(image.ok());
    std::string message = image.error().str();
    CHECK(message.find('\n') == std::string::npos);  // one line
    return message;
}

std::vector<uint8_t> floats_as_bytes(std::initializer_list<float> values) {
    std::vector<uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.begin(), bytes.size());
    return bytes;
}

// Renames the OpEntryPoint literal "main" to "nain" in place (same length, still valid SPIR-V).
SpirvBinary without_main_entry_point(SpirvBinary spirv) {
    for (size_t at = 5; at < spirv.size();) {
        const uint32_t count = spirv[at] >> 16, opcode = spirv[at] & 0xffffu;
        if (count == 0) break;
        if (opcode == 15 /* OpEntryPoint */ && count > 3) spirv[at + 3] = (spirv[at + 3] & ~0xffu) | 'n';
        at += count;
    }
    return spirv;
}

bool is_lavapipe(const DeviceInfo& device) { return device.name.find("llvmpipe") != std::string::npos; }

}  // namespace

TEST_CASE("device listing finds lavapipe", "[runtime][vulkan]") {
    auto devices = list_vulkan_devices();
    INFO((devices.ok() ? std::string() : devices.error().str()));
    REQUIRE(devices.ok());
    REQUIRE_FALSE(devices.value().empty());
    bool found = false;
    for (size_t i = 0; i < devices.value().size(); ++i) {
        const DeviceInfo& device = devices.value()[i];
        CHECK(device.index == i);
        CHECK_FALSE(device.name.empty());
        if (is_lavapipe(device)) {
            found = true;
            CHECK(device.type == "cpu");
        }
    }
    CHECK(found);
    // With no device named, the engine prefers lavapipe.
    CHECK(is_lavapipe(engine().device()));
}

TEST_CASE("devices are chosen by name substring or index, and a miss is an error", "[runtime][vulkan]") {
    auto by_name = create_vulkan_engine(EngineOptions{"LLVMPIPE", false});
    REQUIRE(by_name.ok());
    CHECK(is_lavapipe(by_name.value()->device()));

    const std::string index = std::to_string(engine().device().index);
    auto by_index = create_vulkan_engine(EngineOptions{index, false});
    REQUIRE(by_index.ok());
    CHECK(by_index.value()->device().name == engine().device().name);

    auto missing = create_vulkan_engine(EngineOptions{"no-such-gpu", false});
    REQUIRE_FALSE(missing.ok());
    CHECK_THAT(missing.error().str(), Contains("no-such-gpu") && Contains("llvmpipe"));
    auto out_of_range = create_vulkan_engine(EngineOptions{"999", false});
    REQUIRE_FALSE(out_of_range.ok());
    CHECK_THAT(out_of_range.error().str(), Contains("999"));
}

TEST_CASE("a passthrough shader reproduces its input exactly", "[runtime][vulkan]") {
    // Every value is exactly representable in half precision, so RGBA16F must give it back unchanged.
    Image input = Image::make(5, 3);
    for (int y = 0; y < input.height; ++y) {
        for (int x = 0; x < input.width; ++x) {
            input.set_pixel(x, y, {x / 8.0f, y / 4.0f, (x + y) / 16.0f - 0.25f, 1.0f - x / 32.0f});
        }
    }
    const Image output = render_ok(make_job(kPassthrough, input, 5, 3, OutputFormat::Rgba16Float));
    CHECK(output.rgba == input.rgba);
}

TEST_CASE("uniform buffer values reach the shader", "[runtime][vulkan]") {
    RenderJob job = make_job(kUniformShader, Image{}, 3, 2, OutputFormat::Rgba16Float);
    job.uniform_data = floats_as_bytes({0.25f, 0.75f});  // std140: a at offset 0, b at offset 4
    const Image output = render_ok(job);
    for (int y = 0; y < output.height; ++y) {
        for (int x = 0; x < output.width; ++x) {
            CHECK(output.pixel(x, y) == std::array<float, 4>{0.25f, 0.75f, 0.0f, 1.0f});
        }
    }
}

TEST_CASE("output row 0 is the top row, column 0 the left column", "[runtime][vulkan]") {
    Image input = Image::make(2, 2);
    input.set_pixel(0, 0, {1, 0, 0, 1});  // top: red, green
    input.set_pixel(1, 0, {0, 1, 0, 1});
    input.set_pixel(0, 1, {0, 0, 1, 1});  // bottom: blue, white
    input.set_pixel(1, 1, {1, 1, 1, 1});
    const Image output = render_ok(make_job(kPassthrough, input, 4, 4, OutputFormat::Rgba8Unorm));
    CHECK(output.pixel(0, 0) == std::array<float, 4>{1, 0, 0, 1});
    CHECK(output.pixel(3, 0) == std::array<float, 4>{0, 1, 0, 1});
    CHECK(output.pixel(0, 3) == std::array<float, 4>{0, 0, 1, 1});
    CHECK(output.pixel(3, 3) == std::array<float, 4>{1, 1, 1, 1});
}

TEST_CASE("linear and nearest filtering differ as expected when upscaling", "[runtime][vulkan]") {
    Image input = Image::make(2, 1);
    input.set_pixel(0, 0, {0, 0, 0, 1});
    input.set_pixel(1, 0, {1, 1, 1, 1});

    const Image nearest = render_ok(make_job(kPassthrough, input, 4, 1, OutputFormat::Rgba16Float,
                                             SamplerFilter::Nearest));
    const Image linear = render_ok(make_job(kPassthrough, input, 4, 1, OutputFormat::Rgba16Float,
                                            SamplerFilter::Linear));
    // Output pixel centres sample u = 1/8, 3/8, 5/8, 7/8: texel positions -0.25, 0.25, 0.75, 1.25,
    // which clamp-to-edge turns into 0, 0.25, 0.75, 1 when filtering linearly.
    const float expect_nearest[4] = {0.0f, 0.0f, 1.0f, 1.0f};
    const float expect_linear[4] = {0.0f, 0.25f, 0.75f, 1.0f};
    for (int x = 0; x < 4; ++x) {
        INFO("x = " << x);
        CHECK(nearest.at(x, 0)[0] == expect_nearest[x]);
        CHECK(linear.at(x, 0)[0] == Approx(expect_linear[x]).margin(1.0 / 256));  // subtexel precision
        CHECK(linear.at(x, 0)[3] == 1.0f);
    }
}

TEST_CASE("an HDR input value survives to an RGBA16F output", "[runtime][vulkan]") {
    const Image input = Image::make(1, 1, {4.0f, 2.5f, 0.0f, 1.0f});
    const Image output = render_ok(make_job(kPassthrough, input, 2, 2, OutputFormat::Rgba16Float));
    CHECK(output.pixel(0, 0) == std::array<float, 4>{4.0f, 2.5f, 0.0f, 1.0f});
    CHECK(output.pixel(1, 1) == std::array<float, 4>{4.0f, 2.5f, 0.0f, 1.0f});
}

TEST_CASE("RGBA8 UNORM output is quantised to 1/255 steps and clamped", "[runtime][vulkan]") {
    const Image output =
        render_ok(make_job(constant_shader("vec4(0.3, 0.5, 1.5, -0.25)"), Image{}, 2, 2, OutputFormat::Rgba8Unorm));
    const float* p = output.at(1, 1);
    const float written[3] = {0.3f, 0.5f, 1.0f};  // 1.5 clamps to 1
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c << " = " << p[c]);
        CHECK(std::fabs(p[c] * 255.0f - std::round(p[c] * 255.0f)) < 1e-4f);  // on the byte grid
        CHECK(std::fabs(p[c] - written[c]) <= 1.0f / 255.0f);
    }
    CHECK(p[3] == 0.0f);  // -0.25 clamps to 0
}

TEST_CASE("an sRGB target round-trips through decoding", "[runtime][vulkan]") {
    // Linear 0.5 is stored as sRGB byte 188; the engine decodes it back to about 0.503. A missing
    // encode or decode would be off by about 0.23.
    const Image output =
        render_ok(make_job(constant_shader("vec4(0.5, 0.5, 0.5, 0.5)"), Image{}, 2, 2, OutputFormat::Rgba8Srgb));
    for (int c = 0; c < 4; ++c) {
        INFO("channel " << c << " = " << output.at(0, 0)[c]);
        CHECK(std::fabs(output.at(0, 0)[c] - 0.5f) <= 1.0f / 255.0f);
    }
}

TEST_CASE("rendering is deterministic", "[runtime][vulkan]") {
    Image input = Image::make(3, 3);
    for (size_t i = 0; i < input.rgba.size(); ++i) input.rgba[i] = static_cast<float>(i % 7) / 7.0f;
    const RenderJob job = make_job(kPassthrough, input, 8, 5, OutputFormat::Rgba16Float, SamplerFilter::Linear);
    CHECK(render_ok(job).rgba == render_ok(job).rgba);
}

TEST_CASE("bad jobs return errors and leave the engine usable", "[runtime][vulkan]") {
    const RenderJob good = make_job(kPassthrough, Image::make(2, 2, {0.5f, 0.5f, 0.5f, 1}), 2, 2,
                                    OutputFormat::Rgba8Unorm);

    SECTION("zero size") {
        RenderJob job = good;
        job.width = 0;
        CHECK_THAT(render_error(job), Contains("job.width"));
        job = good;
        job.height = 0;
        CHECK_THAT(render_error(job), Contains("job.height"));
    }
    SECTION("a size over the device limit") {
        RenderJob job = good;
        job.width = 1 << 20;  // beyond any device's maxImageDimension2D
        CHECK_THAT(render_error(job), Contains("job.width"));
        job.width = INT_MAX;
        CHECK_THAT(render_error(job), Contains("job.width"));
    }
    SECTION("empty SPIR-V") {
        RenderJob job = good;
        job.fragment_spirv.clear();
        CHECK_THAT(render_error(job), Contains("job.fragment_spirv") && Contains("empty"));
        job = good;
        job.vertex_spirv.clear();
        CHECK_THAT(render_error(job), Contains("job.vertex_spirv"));
    }
    SECTION("words that are not SPIR-V") {
        RenderJob job = good;
        job.fragment_spirv = {0xdeadbeef, 1, 2, 3, 4, 5, 6};
        CHECK_THAT(render_error(job), Contains("not valid SPIR-V"));
        job.fragment_spirv = good.fragment_spirv;
        job.fragment_spirv.push_back(0x00ff0000);  // an instruction claiming 255 words past the end
        CHECK_THAT(render_error(job), Contains("not valid SPIR-V"));
    }
    SECTION("SPIR-V whose entry point is not 'main'") {
        RenderJob job = good;
        job.fragment_spirv = without_main_entry_point(good.fragment_spirv);
        CHECK_THAT(render_error(job), Contains("'main'") && Contains("'nain'"));
    }
    SECTION("the stages swapped") {
        RenderJob job = good;
        std::swap(job.vertex_spirv, job.fragment_spirv);
        CHECK_THAT(render_error(job), Contains("entry point"));
    }
    SECTION("a uniform block the job does not fill") {
        RenderJob job = make_job(kUniformShader, Image{}, 2, 2, OutputFormat::Rgba8Unorm);
        CHECK_THAT(render_error(job), Contains("job.uniform_data"));
        job.uniform_data = floats_as_bytes({0.25f});  // the block needs 8 bytes
        CHECK_THAT(render_error(job), Contains("8 bytes"));
    }
    SECTION("a texture at a binding the job does not provide") {
        RenderJob job = good;
        job.texture_binding = 3;
        CHECK_THAT(render_error(job), Contains("binding 1"));
        job = good;
        job.descriptor_set = 1;
        CHECK_THAT(render_error(job), Contains("job.descriptor_set"));
    }
    SECTION("an input whose pixel buffer does not match its size") {
        RenderJob job = good;
        Image short_input = *good.input;
        short_input.rgba.pop_back();
        job.input = std::move(short_input);
        CHECK_THAT(render_error(job), Contains("job.input"));
    }
    // After any of the above, a good job still renders.
    const Image output = render_ok(good);
    CHECK(output.at(1, 1)[0] == Approx(0.5).margin(1.0 / 255));
}

TEST_CASE("resources can live in another descriptor set and bindings", "[runtime][vulkan]") {
    const char* shader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(std140, set = 2, binding = 5) uniform Params { vec4 tint; } p;
layout(set = 2, binding = 7) uniform sampler2D source;
void main() { fragColor = texture(source, vTexCoord) * p.tint; }
)";
    RenderJob job = make_job(shader, Image::make(1, 1, {1.0f, 0.5f, 0.25f, 1.0f}), 2, 2, OutputFormat::Rgba16Float);
    job.descriptor_set = 2;
    job.uniform_binding = 5;
    job.texture_binding = 7;
    job.uniform_data = floats_as_bytes({2.0f, 2.0f, 2.0f, 0.5f});
    const Image output = render_ok(job);
    CHECK(output.pixel(1, 0) == std::array<float, 4>{2.0f, 1.0f, 0.5f, 0.5f});
}

// ---- several textures, wrap modes, viewport and clear colour -------------------------------------

namespace {

using P = std::array<float, 4>;

// A width x 1 image whose red channel holds `values` (the other channels 0, alpha 1).
Image row_of(std::initializer_list<float> values) {
    Image image = Image::make(static_cast<int>(values.size()), 1);
    int x = 0;
    for (float v : values) image.set_pixel(x++, 0, {v, 0.0f, 0.0f, 1.0f});
    return image;
}

TextureInput texture_input(std::string name, uint32_t binding, Image image, SamplerFilter filter,
                           WrapMode wrap = WrapMode::ClampToEdge) {
    TextureInput texture;
    texture.name = std::move(name);
    texture.binding = binding;
    texture.image = std::move(image);
    texture.filter = filter;
    texture.wrap = wrap;
    return texture;
}

Diagnostic render_diagnostic(const RenderJob& job) {
    auto image = engine().render(job);
    REQUIRE_FALSE(image.ok());
    CHECK(image.error().str().find('\n') == std::string::npos);  // one line
    return image.error();
}

}  // namespace

TEST_CASE("extra textures are read at their own bindings with their own filters", "[runtime][vulkan]") {
    const char* shader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
layout(set = 0, binding = 3) uniform sampler2D texA;
layout(set = 0, binding = 5) uniform sampler2D texB;
void main() {
    fragColor = vec4(texture(texA, vTexCoord).r, texture(texB, vTexCoord).r, texture(source, vTexCoord).r, 1.0);
}
)";
    // Two output columns sample u = 1/4 and 3/4: the centres of texA's two texels (nearest), and
    // exactly halfway between texB's texels 0|1 and 2|3 (linear: their averages).
    RenderJob job = make_job(shader, Image::make(1, 1, {0.125f, 0, 0, 1}), 2, 2, OutputFormat::Rgba16Float);
    job.textures.push_back(texture_input("texA", 3, row_of({0.25f, 0.75f}), SamplerFilter::Nearest));
    job.textures.push_back(texture_input("texB", 5, row_of({0.0f, 1.0f, 0.5f, 0.25f}), SamplerFilter::Linear));
    const Image output = render_ok(job);
    for (int y = 0; y < 2; ++y) {
        INFO("row " << y);
        CHECK(output.pixel(0, y)[0] == 0.25f);
        CHECK(output.pixel(1, y)[0] == 0.75f);
        CHECK(output.pixel(0, y)[1] == Approx(0.5).margin(1.0 / 256));
        CHECK(output.pixel(1, y)[1] == Approx(0.375).margin(1.0 / 256));
        CHECK(output.pixel(0, y)[2] == 0.125f);  // the main input is still at texture_binding
        CHECK(output.pixel(1, y)[2] == 0.125f);
    }
}

TEST_CASE("the engine keeps uploads and pipelines only for what is really the same", "[runtime][vulkan]") {
    // The engine keeps a shared image's upload and a built pass for later jobs: each job here
    // shares as much as it can with the one before and differs in one thing, which must show.
    const std::string tex_shader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
layout(set = 0, binding = 3) uniform sampler2D lut;
void main() { fragColor = vec4(texture(lut, vTexCoord).r, SCALE * texture(source, vTexCoord).r, 0.0, 1.0); }
)";
    auto shader = [&](const char* scale) {
        std::string text = tex_shader;
        text.replace(text.find("SCALE"), 5, scale);
        return text;
    };
    const SharedImage lut_a = row_of({0.25f, 0.75f});
    const SharedImage lut_b = row_of({0.5f, 1.0f});  // same size, other texels
    // Four columns sample u = 1/8, 3/8, 5/8, 7/8 of the two-texel LUT.
    RenderJob job = make_job(shader("1.0"), Image::make(1, 1, {0.125f, 0, 0, 1}), 4, 1, OutputFormat::Rgba16Float);
    job.textures.push_back(texture_input("lut", 3, Image{}, SamplerFilter::Nearest));
    job.textures[0].image = lut_a;
    const Image first = render_ok(job);
    CHECK(first.pixel(0, 0) == P{0.25f, 0.125f, 0.0f, 1.0f});
    CHECK(first.pixel(3, 0) == P{0.75f, 0.125f, 0.0f, 1.0f});
    CHECK(render_ok(job).rgba == first.rgba);  // the kept upload and pass draw the same again

    job.textures[0].image = lut_b;  // another image: its own upload
    CHECK(render_ok(job).pixel(3, 0) == P{1.0f, 0.125f, 0.0f, 1.0f});
    job.textures[0].filter = SamplerFilter::Linear;  // the same image, another sampler
    CHECK(render_ok(job).pixel(1, 0)[0] == Approx(0.625).margin(1.0 / 256));  // 3/4 of 0.5 + 1/4 of 1
    job.textures[0].filter = SamplerFilter::Nearest;

    RenderJob other = make_job(shader("2.0"), Image::make(1, 1, {0.125f, 0, 0, 1}), 4, 1, OutputFormat::Rgba16Float);
    other.textures = job.textures;  // the same layout and texture, another fragment module
    CHECK(render_ok(other).pixel(0, 0) == P{0.5f, 0.25f, 0.0f, 1.0f});
    other.format = OutputFormat::Rgba8Unorm;  // another target format: another pass
    CHECK(render_ok(other).pixel(0, 0)[1] == Approx(64.0 / 255).margin(0.5 / 255));
    other.width = 1;  // another viewport (u = 1/2: texel 1): another pass
    const Image narrow = render_ok(other);
    CHECK(narrow.width == 1);
    CHECK(narrow.pixel(0, 0)[0] == Approx(1.0).margin(0.5 / 255));

    // The cache does not keep a picture alive: once the last handle to an image is gone, a new
    // image (the allocator hands back the same addresses, many times over) draws its own texels.
    RenderJob fresh = make_job(shader("1.0"), Image::make(1, 1, {0.125f, 0, 0, 1}), 4, 1, OutputFormat::Rgba16Float);
    fresh.textures.push_back(texture_input("lut", 3, Image{}, SamplerFilter::Nearest));
    for (int round = 0; round < 8; ++round) {
        INFO("round " << round);
        const float value = 0.125f * static_cast<float>(round + 1);
        fresh.textures[0].image = row_of({value, value});  // the earlier round's image is released here
        CHECK(render_ok(fresh).pixel(0, 0)[0] == value);
    }
}

TEST_CASE("each wrap mode returns its texel outside 0..1, for the input and an extra texture", "[runtime][vulkan]") {
    // Column 0 samples u = -0.375, column 1 u = 1.375: the centres of texels -2 and 5 of a 4-texel
    // row (texel centres, not the edges at -0.25 / 1.25, where nearest may round either way).
    const char* shader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
layout(set = 0, binding = 2) uniform sampler2D extra;
void main() {
    vec2 uv = vec2(vTexCoord.x < 0.5 ? -0.375 : 1.375, 0.5);
    fragColor = vec4(texture(source, uv).r, texture(extra, uv).r, 0.0, 1.0);
}
)";
    const Image texels = row_of({0.125f, 0.25f, 0.5f, 1.0f});
    struct Case {
        WrapMode wrap;
        float left, right;
    };
    const Case cases[] = {{WrapMode::ClampToEdge, 0.125f, 1.0f},  // texel 0 / texel 3
                          {WrapMode::Repeat, 0.5f, 0.25f},        // -2 -> 2, 5 -> 1
                          {WrapMode::MirroredRepeat, 0.25f, 0.5f}};  // -2 -> 1, 5 -> 2
    RenderJob job = make_job(shader, texels, 2, 1, OutputFormat::Rgba16Float, SamplerFilter::Nearest);
    for (const Case& c : cases) {
        INFO("wrap mode " << static_cast<int>(c.wrap));
        job.wrap = c.wrap;
        job.textures = {texture_input("extra", 2, texels, SamplerFilter::Nearest, c.wrap)};
        const Image output = render_ok(job);
        CHECK(output.pixel(0, 0) == P{c.left, c.left, 0.0f, 1.0f});
        CHECK(output.pixel(1, 0) == P{c.right, c.right, 0.0f, 1.0f});
    }
}

TEST_CASE("a viewport draws a pasted full render and keeps the clear colour around it", "[runtime][vulkan]") {
    const char* shader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() { fragColor = vec4(texture(source, vTexCoord).rg, vTexCoord); }
)";
    Image input = Image::make(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) input.set_pixel(x, y, {(x + 1) / 8.0f, (y + 1) / 4.0f, 0.0f, 1.0f});
    const Image full = render_ok(make_job(shader, input, 8, 4, OutputFormat::Rgba16Float));

    RenderJob job = make_job(shader, input, 16, 8, OutputFormat::Rgba16Float);
    job.viewport = {4, 2, 8, 4};
    job.clear_color = {0, 0, 0, 1};
    const Image output = render_ok(job);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 16; ++x) {
            INFO("pixel " << x << ", " << y);
            const bool inside = x >= 4 && x < 12 && y >= 2 && y < 6;
            CHECK(output.pixel(x, y) == (inside ? full.pixel(x - 4, y - 2) : P{0, 0, 0, 1}));
        }
    }
    CHECK(output.pixel(4, 2)[0] == input.pixel(0, 0)[0]);  // the viewport's top-left is the input's
    CHECK(output.pixel(4, 2)[1] == input.pixel(0, 0)[1]);
    // The clear colour is linear like the shader's output: an sRGB target stores it encoded.
    job.format = OutputFormat::Rgba8Srgb;
    job.clear_color = {0.5f, 0.25f, 0.0f, 1.0f};
    const Image srgb = render_ok(job);
    CHECK(srgb.pixel(15, 7)[0] == Approx(0.5).margin(0.004));
    CHECK(srgb.pixel(15, 7)[1] == Approx(0.25).margin(0.004));
}

TEST_CASE("bad textures, viewports and clear colours are input errors", "[runtime][vulkan]") {
    const char* shader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
layout(set = 0, binding = 2) uniform sampler2D lut;
void main() { fragColor = texture(source, vTexCoord) + texture(lut, vTexCoord); }
)";
    RenderJob good = make_job(shader, Image::make(2, 2, {0.25f, 0, 0, 1}), 16, 8, OutputFormat::Rgba16Float);
    good.textures = {texture_input("lut", 2, Image::make(2, 1, {0.5f, 0, 0, 0}), SamplerFilter::Linear)};
    auto expect = [](const RenderJob& job, const std::string& field) {
        const Diagnostic error = render_diagnostic(job);
        INFO(error.str());
        CHECK(error.kind == ErrorKind::Input);
        CHECK(error.field == field);
        return error.str();
    };
    RenderJob job = good;
    job.viewport = {10, 2, 8, 4};  // 10 + 8 > 16
    expect(job, "job.viewport");
    job.viewport = {4, 2, 0, 4};  // a zero side
    expect(job, "job.viewport");
    job.viewport = {-1, 0, 4, 4};
    expect(job, "job.viewport");

    job = good;
    job.textures.push_back(texture_input("other", 2, Image{}, SamplerFilter::Nearest));
    CHECK_THAT(expect(job, "job.textures[1].binding"), Contains("job.textures[0].binding"));
    job = good;
    job.textures[0].binding = 1;  // the main input's
    expect(job, "job.textures[0].binding");
    job = good;
    job.textures[0].binding = 0;
    job.uniform_data = floats_as_bytes({1.0f, 2.0f, 3.0f, 4.0f});  // the uniform buffer's
    expect(job, "job.textures[0].binding");

    job = good;
    {
        Image broken = *job.textures[0].image;
        broken.rgba.pop_back();
        job.textures[0].image = std::move(broken);
    }
    expect(job, "job.textures[0].image");
    job.textures[0].image = Image::make(kMaxImageDimension + 1, 1);
    expect(job, "job.textures[0].image");

    job = good;
    job.clear_color[2] = std::nanf("");
    expect(job, "job.clear_color");
    job.clear_color[2] = INFINITY;
    expect(job, "job.clear_color");

    // A sampler the shader declares that neither the input nor a texture provides, named.
    job = good;
    job.textures[0].binding = 4;
    CHECK_THAT(expect(job, "job.texture_binding"), Contains("'lut'") && Contains("binding 2") && Contains("1, 4"));

    const Image output = render_ok(good);  // the engine is still usable
    CHECK(output.pixel(0, 0)[0] == 0.75f);
}

TEST_CASE("memory that goes back to the pool is reused and never shows through", "[runtime][vulkan]") {
    // A job's freed image and buffers go back to the context's pool and the next job of the same
    // sizes takes them: what an earlier job drew or read back must never reach a later picture.
    RenderJob white = make_job(constant_shader("vec4(1.0)"), Image::make(1, 1), 8, 4, OutputFormat::Rgba8Unorm);
    CHECK(render_ok(white).pixel(7, 3) == P{1.0f, 1.0f, 1.0f, 1.0f});
    // The same size: discarded pixels keep the pass's cleared (transparent black) contents.
    RenderJob half = make_job("#version 450\nlayout(location = 0) in vec2 vTexCoord;\nlayout(location = 0) out vec4 fragColor;\n"
                              "void main() { if (vTexCoord.x > 0.5) discard; fragColor = vec4(0.0, 1.0, 0.0, 1.0); }\n",
                              Image::make(1, 1), 8, 4, OutputFormat::Rgba8Unorm);
    for (int round = 0; round < 3; ++round) {
        render_ok(white);
        const Image drawn = render_ok(half);
        CHECK(drawn.pixel(0, 0) == P{0.0f, 1.0f, 0.0f, 1.0f});
        CHECK(drawn.pixel(7, 3) == P{0.0f, 0.0f, 0.0f, 0.0f});
    }
    // An input upload of a size met before carries its own texels.
    RenderJob copy = make_job(kPassthrough, Image::make(8, 4, {0.25f, 0.5f, 0.75f, 1.0f}), 8, 4, OutputFormat::Rgba16Float);
    CHECK(render_ok(copy).pixel(5, 2) == P{0.25f, 0.5f, 0.75f, 1.0f});
    copy.input = Image::make(8, 4, {0.5f, 0.25f, 0.0f, 1.0f});
    CHECK(render_ok(copy).pixel(5, 2) == P{0.5f, 0.25f, 0.0f, 1.0f});
}

TEST_CASE("the memory pool hands a block back only for its own type and size, within its budget", "[runtime][vulkan]") {
    auto context = vulkan::VulkanContext::create(EngineOptions{});
    INFO((context.ok() ? std::string() : context.error().str()));
    REQUIRE(context.ok());
    const VkPhysicalDeviceMemoryProperties& memory = context.value()->memory_properties();
    REQUIRE(memory.memoryTypeCount > 0);
    vulkan::MemoryPool pool(context.value()->device(), 1 << 20);
    auto take = [&](uint32_t type, VkDeviceSize size) {
        auto block = pool.take(type, size);
        INFO((block.ok() ? std::string() : block.error().str()));
        REQUIRE(block.ok());
        return std::move(block).value();
    };
    auto first = take(0, 4096);
    const VkDeviceMemory handle = first.get();
    first.reset();
    auto again = take(0, 4096);
    CHECK(again.get() == handle);  // the same type and size: the kept block
    auto other = take(0, 8192);     // another size: a block of its own
    CHECK(other.get() != handle);
    again.reset();
    other.reset();
    CHECK(pool.kept_bytes() == 4096 + 8192);
    // Within the budget (1 MiB): the oldest blocks go first, and a block over a quarter of it is
    // freed at once, not kept.
    std::vector<vulkan::PooledMemory> blocks;
    for (int i = 0; i < 6; ++i) blocks.push_back(take(0, 200 << 10));
    blocks.clear();
    CHECK(pool.kept_bytes() <= (1u << 20));
    CHECK(pool.kept_bytes() >= 4 * (200u << 10));
    const VkDeviceSize before = pool.kept_bytes();
    take(0, 300 << 10).reset();
    CHECK(pool.kept_bytes() == before);
    pool.clear();
    CHECK(pool.kept_bytes() == 0);
}

TEST_CASE("a float target kept on the device is sampled by later jobs exactly as its read-back, an 8-bit one is read back", "[runtime][vulkan]") {
    // A pass's output that only later passes read may stay on the device (keep_on_device): its
    // readers must then draw what they draw from the read-back picture, to the bit, through every
    // way a reader samples (nearest, linear, a mip chain, the main input or an extra texture).
    const std::string pattern = constant_shader(
        "vec4(vTexCoord * 3.7 - 0.3, sin(gl_FragCoord.x * 1.37 + gl_FragCoord.y * 0.71) * 1000.0, 1.0 / 3.0 + vTexCoord.x)");
    const std::string reader = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
layout(set = 0, binding = 3) uniform sampler2D extra;
void main() { fragColor = texture(source, vTexCoord * 1.3 - 0.1) + 0.5 * textureLod(extra, vTexCoord.yx, 1.7); }
)";
    for (OutputFormat format : {OutputFormat::Rgba16Float, OutputFormat::Rgba32Float, OutputFormat::R16Float, OutputFormat::Rg16Float,
                                OutputFormat::Rgba8Unorm}) {
        INFO("format " << static_cast<int>(format));
        RenderJob pass = make_job(pattern, Image{}, 19, 13, format);
        const SharedImage read = render_ok(pass);
        pass.keep_on_device = true;
        auto kept_image = engine().render(pass);
        REQUIRE(kept_image.ok());
        const SharedImage kept = std::move(kept_image.value());
        CHECK(kept->width == 19);
        CHECK(kept->height == 13);
        if (format == OutputFormat::Rgba8Unorm) {  // read back: the device's byte-to-float is not byte / 255 to the bit
            CHECK_FALSE(kept->device);
            CHECK(kept->rgba == read->rgba);
            continue;
        }
        REQUIRE(kept->device);
        CHECK(kept->rgba.empty());
        for (SamplerFilter filter : {SamplerFilter::Nearest, SamplerFilter::Linear}) {
            for (bool mipmap : {false, true}) {
                INFO("filter " << static_cast<int>(filter) << ", mipmap " << mipmap);
                auto job_from = [&](const SharedImage& picture) {
                    RenderJob job = make_job(reader, Image{}, 29, 17, OutputFormat::Rgba32Float, filter);
                    job.input = picture;
                    job.mipmap = mipmap;
                    job.textures.push_back(texture_input("extra", 3, Image{}, SamplerFilter::Linear, WrapMode::Repeat));
                    job.textures[0].image = picture;
                    job.textures[0].mipmap = true;
                    return job;
                };
                CHECK(render_ok(job_from(kept)).rgba == render_ok(job_from(read)).rgba);
            }
        }
    }

    // Another engine cannot sample what this one kept: refused, not read as texels that are not there.
    RenderJob pass = make_job(pattern, Image{}, 8, 8, OutputFormat::Rgba16Float);
    pass.keep_on_device = true;
    auto kept = engine().render(pass);
    REQUIRE(kept.ok());
    REQUIRE(kept.value().device);
    auto other = create_vulkan_engine(EngineOptions{});
    REQUIRE(other.ok());
    RenderJob job = make_job(kPassthrough, std::move(kept.value()), 8, 8, OutputFormat::Rgba16Float);
    auto refused = other.value()->render(job);
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().str(), Contains("another engine kept on its device"));
}
