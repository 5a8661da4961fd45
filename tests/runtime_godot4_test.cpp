// A real Godot 4 (4.6's official web build in headless Chromium, runtime/godot4): the engine's
// conventions (UV top-left, the read-back's orientation and its 8-bit step), its own shader
// compiler refusing what the shim accepts, and every snapshot construct's Godot 4 shader compiled
// by it. One Godot 4 serves the whole test process (shared_godot4_server), as it serves a validate
// run.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "crtforge/files.hpp"
#include "crtforge/runtime/godot4_engine.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_shim.hpp"

using namespace crtforge;
using Catch::Matchers::Contains;

namespace {

// A 2 x 2 picture: red, green / blue, white (row 0 = top).
Image quadrants() {
    Image image = Image::make(2, 2);
    const float px[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 4; ++c) image.rgba[static_cast<size_t>(i * 4 + c)] = px[i][c];
    return image;
}

const float* pixel(const Image& image, int x, int y) { return &image.rgba[static_cast<size_t>((y * image.width + x) * 4)]; }

}  // namespace

TEST_CASE("godot4: TEXTURE and UV start at the top-left, the read-back is top row first, 8 bits a channel", "[godot4]") {
    Godot4Job job;
    job.shader_code =
        "shader_type canvas_item;\nuniform float gain = 1.0;\n"
        "void fragment() { COLOR = vec4(texture(TEXTURE, UV).rgb * gain, 1.0); }\n";
    job.input = quadrants();
    job.filter = SamplerFilter::Nearest;
    job.width = 4;
    job.height = 4;
    job.params["gain"] = 0.5;
    auto image = shared_godot4_server().render(job);
    INFO((image.ok() ? std::string() : image.error().str()));
    REQUIRE(image.ok());
    const Image& out = image.value();
    REQUIRE(out.width == 4);
    REQUIRE(out.height == 4);
    // Top-left red, top-right green, bottom-left blue, at the gain the host set.
    CHECK(pixel(out, 0, 0)[0] == Approx(0.5).margin(1.0 / 255));
    CHECK(pixel(out, 3, 0)[1] == Approx(0.5).margin(1.0 / 255));
    CHECK(pixel(out, 0, 3)[2] == Approx(0.5).margin(1.0 / 255));
    CHECK(pixel(out, 3, 3)[0] == Approx(0.5).margin(1.0 / 255));
    // The viewport stores 8 bits: every value is a multiple of 1/255.
    for (float v : out.rgba) CHECK(std::fabs(v * 255.0f - std::round(v * 255.0f)) < 1e-3f);
}

TEST_CASE("godot4: a shader Godot 4 refuses but the shim accepts fails the godot4 consumer, with its line", "[godot4][errors]") {
    // A global without an initialiser (SPIRV-Cross's printing of OpUndef): GLSL, so the shim takes
    // it; Godot 4 has only global constants and says "Expected initialization of constant".
    OutputFile shader;
    shader.path = "addons/crtforge/refused.gdshader";
    shader.stage = ShaderStage::Fragment;
    shader.role = "shader";
    shader.data = "shader_type canvas_item;\n\nvec4 _1032;\n\nvoid fragment()\n{\n    COLOR = texture(TEXTURE, UV) + _1032 * 0.0;\n}\n";
    ConsumerEngines engines(EngineOptions{});
    REQUIRE(consumers::compile_through_shim(shader.data, 4, engines).ok());
    auto refused = godot4_consumer().compile(shader, engines);
    REQUIRE_FALSE(refused.ok());
    CHECK(refused.error().kind == ErrorKind::Validation);
    CHECK_THAT(refused.error().message, Contains("Godot 4 rejected the shader") && Contains("initialization of constant"));
    CHECK(refused.error().line == 3);
    // The same shader with the global as a constant compiles.
    shader.data.replace(shader.data.find("vec4 _1032;"), 11, "const vec4 _1032 = vec4(0.0);");
    CHECK(godot4_consumer().compile(shader, engines).ok());
}

TEST_CASE("real Godot 4 accepts the Godot 4 shader of every snapshot construct", "[godot4]") {
    // One construct family per snapshot preset (loops, loop-carried values, int switches, the
    // optimiser's undefined lanes): each exported Godot 4 shader, node and screen mode, compiled
    // by the engine itself.
    const std::string dir = std::string(CRTFORGE_SOURCE_DIR) + "/tests/snapshots/expected/godot4/addons/crtforge";
    ConsumerEngines engines(EngineOptions{});
    size_t compiled = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".gdshader") continue;
        OutputFile shader;
        shader.path = entry.path().filename().string();
        shader.data = read_text_file(entry.path().string()).value();
        INFO(shader.path);
        auto result = godot4_consumer().compile(shader, engines);
        if (!result.ok()) UNSCOPED_INFO(result.error().str());
        CHECK(result.ok());
        ++compiled;
    }
    CHECK(compiled >= 16);
}
