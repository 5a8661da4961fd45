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
        job.input.rgba.pop_back();
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
