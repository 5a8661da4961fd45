// The Godot 3 engine: canvas_item shaders rendered by a real Godot 3 (Debian's godot3 on a private
// Xvfb, Mesa llvmpipe) and read back. Every render starts one Godot process (about 2 s), so each
// test renders once and checks everything that render can show. The conventions pinned here
// (UV top-left, FRAGCOORD bottom-left, half-float read-back) are the ones the Godot 3 emitter
// relies on.
#include <catch2/catch.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <string>

#include "crtforge/runtime/godot3_engine.hpp"
#include "targets/godot/godot3_syntax.hpp"

namespace {

using namespace crtforge;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using P = std::array<float, 4>;

Godot3Job make_job(std::string code, Image input, int width, int height,
                   SamplerFilter filter = SamplerFilter::Nearest) {
    Godot3Job job;
    job.shader_code = std::move(code);
    job.input = std::move(input);
    job.filter = filter;
    job.width = width;
    job.height = height;
    return job;
}

Image render_ok(const Godot3Job& job) {
    const auto start = std::chrono::steady_clock::now();
    auto image = render_godot3(job);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO((image.ok() ? std::string() : image.error().str()));
    REQUIRE(image.ok());
    REQUIRE(image.value().width == job.width);
    REQUIRE(image.value().height == job.height);
    REQUIRE(image.value().consistent());
    UNSCOPED_INFO("Godot 3 render took " << seconds << " s");
    return std::move(image).value();
}

Diagnostic render_error(const Godot3Job& job) {
    auto image = render_godot3(job);
    REQUIRE_FALSE(image.ok());
    const Diagnostic& error = image.error();
    CHECK(error.str().find('\n') == std::string::npos);  // one line
    return error;
}

const char* const kPassthrough = "shader_type canvas_item; void fragment() { COLOR = texture(TEXTURE, UV); }\n";

}  // namespace

TEST_CASE("godot3: the installed Godot 3 reports its version", "[godot3]") {
    const std::string version = godot3_version();
    INFO("install the Debian packages godot3 and xvfb (scripts/setup.sh)");
    REQUIRE_FALSE(version.empty());
    CHECK_THAT(version, StartsWith("3."));
}

TEST_CASE("godot3: a passthrough shader reproduces the input, top row on top, HDR intact", "[godot3]") {
    // 3x3: red top row, blue bottom row, a middle row with values an 8-bit target would clamp.
    Image input = Image::make(3, 3);
    for (int x = 0; x < 3; ++x) {
        input.set_pixel(x, 0, {1, 0, 0, 1});
        input.set_pixel(x, 2, {0, 0, 1, 1});
    }
    input.set_pixel(0, 1, {3.0f, 0.25f, 0.5f, 1});      // HDR survives (RGBA16F viewport)
    input.set_pixel(1, 1, {-0.5f, 0.125f, 1.5f, 1});    // so do negative values
    input.set_pixel(2, 1, {0.3f, 0.6f, 0.9f, 1});       // non-dyadic: half-float precision
    const Image out = render_ok(make_job(kPassthrough, input, 3, 3));
    for (int x = 0; x < 3; ++x) {
        CHECK(out.pixel(x, 0) == P{1, 0, 0, 1});
        CHECK(out.pixel(x, 2) == P{0, 0, 1, 1});
    }
    CHECK(out.pixel(0, 1) == P{3.0f, 0.25f, 0.5f, 1});
    CHECK(out.pixel(1, 1) == P{-0.5f, 0.125f, 1.5f, 1});
    for (int c = 0; c < 3; ++c) {
        // Read back through half floats, which llvmpipe rounds toward zero: within 2^-10 relative,
        // far tighter than 1/255 (0.3 comes back as 0.2998).
        CHECK(std::fabs(out.pixel(2, 1)[c] - input.pixel(2, 1)[c]) <= input.pixel(2, 1)[c] / 1024.0f);
    }
}

TEST_CASE("godot3: a float uniform reaches the shader", "[godot3]") {
    Godot3Job job = make_job("shader_type canvas_item;\nuniform float gain = 1.0;\n"
                             "void fragment() { COLOR = vec4(vec3(gain), 1.0); }\n",
                             Image{}, 2, 2);
    job.params["gain"] = 0.25;
    const Image out = render_ok(job);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) CHECK(out.pixel(x, y) == P{0.25f, 0.25f, 0.25f, 1});
}

TEST_CASE("godot3: a colour uniform reaches a vec4 hint_color", "[godot3]") {
    // Godot 3.2 allows hint_color on vec4 only; the engine passes alpha 1.
    Godot3Job job = make_job("shader_type canvas_item;\nuniform vec4 tint : hint_color;\n"
                             "void fragment() { COLOR = tint; }\n",
                             Image{}, 2, 2);
    job.params["tint"] = Color{0.25, 0.5, 0.75};
    const Image out = render_ok(job);
    CHECK(out.pixel(0, 0) == P{0.25f, 0.5f, 0.75f, 1});
    CHECK(out.pixel(1, 1) == P{0.25f, 0.5f, 0.75f, 1});
}

TEST_CASE("godot3: linear filtering interpolates when upscaling 2x1 to 4x1", "[godot3]") {
    // A one-pixel-high output also takes the runner's padded-viewport path.
    Image input = Image::make(2, 1);
    input.set_pixel(0, 0, {0, 0, 0, 1});
    input.set_pixel(1, 0, {1, 0.5f, 2, 1});
    const Image out = render_ok(make_job(kPassthrough, input, 4, 1, SamplerFilter::Linear));
    // Samples at u = 1/8, 3/8, 5/8, 7/8 -> texel positions 0.25 .. 1.75, clamped to the edge.
    const std::array<float, 4> weight{0.0f, 0.25f, 0.75f, 1.0f};
    for (int x = 0; x < 4; ++x) {
        INFO("x = " << x);
        CHECK(out.pixel(x, 0)[0] == Approx(weight[x]).margin(1e-3));
        CHECK(out.pixel(x, 0)[1] == Approx(0.5f * weight[x]).margin(1e-3));
        CHECK(out.pixel(x, 0)[2] == Approx(2.0f * weight[x]).margin(2e-3));
        CHECK(out.pixel(x, 0)[3] == 1.0f);
    }
}

TEST_CASE("godot3: UV is top-left, FRAGCOORD and SCREEN_UV bottom-left, and the pixel sizes", "[godot3]") {
    // blend_disabled: COLOR is stored as written (the default blend_mix would give rgb * alpha).
    const Image out = render_ok(make_job("shader_type canvas_item;\nrender_mode blend_disabled;\n"
                                         "void fragment() { COLOR = vec4(UV.y, FRAGCOORD.y / 2.0, "
                                         "TEXTURE_PIXEL_SIZE.x, SCREEN_PIXEL_SIZE.y); }\n",
                                         Image::make(4, 4, {0, 0, 0, 1}), 2, 2));
    CHECK(out.pixel(0, 0) == P{0.25f, 0.75f, 0.25f, 0.5f});  // top row: UV.y = 1/4, FRAGCOORD.y = 1.5
    CHECK(out.pixel(1, 1) == P{0.75f, 0.25f, 0.25f, 0.5f});  // bottom row: UV.y = 3/4, FRAGCOORD.y = 0.5
}

TEST_CASE("godot3: a shader with a syntax error is a one-line validation error", "[godot3]") {
    const Diagnostic error = render_error(make_job("shader_type canvas_item;\nvoid fragment() {\n"
                                                   "    COLOR = vec4(1.0) +;\n}\n",
                                                   Image{}, 2, 2));
    CHECK(error.kind == ErrorKind::Validation);
    CHECK_THAT(error.message, StartsWith("Godot 3 rejected the shader: line 3: "));
}

TEST_CASE("godot3: a param the shader does not declare is an input error", "[godot3]") {
    Godot3Job job = make_job(kPassthrough, Image{}, 2, 2);
    job.params["gian"] = 0.5;
    const Diagnostic error = render_error(job);
    CHECK(error.kind == ErrorKind::Input);
    CHECK_THAT(error.message, Contains("'gian'"));
}

TEST_CASE("godot3: a render that runs past its timeout is killed and reported", "[godot3]") {
    // Godot alone needs over a second to start, and llvmpipe takes minutes over this array.
    Godot3Job job = make_job("shader_type canvas_item;\nvoid fragment() {\n    float a[200000];\n"
                             "    a[0] = 1.0;\n    COLOR = vec4(a[int(UV.x * 199999.0)]);\n}\n",
                             Image{}, 2, 2);
    job.timeout_seconds = 1;
    const auto start = std::chrono::steady_clock::now();
    const Diagnostic error = render_error(job);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
    CHECK(error.kind == ErrorKind::Validation);
    CHECK_THAT(error.message, Contains("did not finish within 1 s"));
}

TEST_CASE("godot3: bad jobs are refused before Godot starts", "[godot3]") {
    Godot3Job job = make_job(kPassthrough, Image{}, 0, 2);
    Diagnostic error = render_error(job);
    CHECK(error.kind == ErrorKind::Input);
    CHECK(error.field == "job.width");

    job = make_job(kPassthrough, Image{}, 2, 2);
    job.params["mode"] = std::string("shadow");
    error = render_error(job);
    CHECK(error.field == "job.params");
    CHECK_THAT(error.message, Contains("enum"));

    job = make_job("", Image{}, 2, 2);
    error = render_error(job);
    CHECK(error.field == "job.shader_code");
}

TEST_CASE("godot3: one server renders many jobs, and a bad job or a hung one does not poison the next", "[godot3][server]") {
    Godot3Server server;
    Image input = Image::make(2, 2);
    input.set_pixel(0, 0, {0.25f, 0.5f, 0.75f, 1.0f});
    input.set_pixel(1, 1, {1.0f, 0.0f, 0.0f, 1.0f});
    auto first = server.render(make_job(kPassthrough, input, 2, 2));
    INFO((first.ok() ? std::string() : first.error().str()));
    REQUIRE(first.ok());
    CHECK(first.value().at(0, 0)[1] == Approx(0.5f).margin(1e-3));

    // A rejected shader is that job's one-line error, not the end of the server.
    auto rejected = server.render(make_job("shader_type canvas_item; void fragment() { COLOR = ; }\n", input, 2, 2));
    REQUIRE_FALSE(rejected.ok());
    CHECK_THAT(rejected.error().message, Contains("Godot 3 rejected the shader"));
    CHECK(rejected.error().str().find('\n') == std::string::npos);

    // A uniform per job: the same process, each job's own value.
    for (float value : {0.2f, 0.6f}) {
        Godot3Job job = make_job("shader_type canvas_item; uniform float v; void fragment() { COLOR = vec4(v, 0.0, 0.0, 1.0); }\n",
                                 input, 3, 2);
        job.params["v"] = static_cast<double>(value);
        auto image = server.render(job);
        INFO((image.ok() ? std::string() : image.error().str()));
        REQUIRE(image.ok());
        CHECK(image.value().at(2, 1)[0] == Approx(value).margin(1e-3));
    }

    // A job past its timeout kills the process; the next job starts a fresh one.
    Godot3Job hang = make_job("shader_type canvas_item; void fragment() { float x = 0.0; for (int i = 0; i < 2000000000; i++) "
                              "{ x += sin(float(i)); } COLOR = vec4(x); }\n",
                              input, 64, 64);
    hang.timeout_seconds = 3;
    hang.frames = 30;
    auto hung = server.render(hang);
    REQUIRE_FALSE(hung.ok());
    auto after = server.render(make_job(kPassthrough, input, 2, 2));
    INFO((after.ok() ? std::string() : after.error().str()));
    REQUIRE(after.ok());
    CHECK(after.value().at(1, 1)[0] == Approx(1.0f).margin(1e-3));
}

// The shapes SPIRV-Cross prints that Godot 3.2.3's parser refuses as they are (loops with no
// initialiser, as in nis's scaler, no step, or `for (;;)` left by a break; an array declared from
// another, or assigned a constructor as in crt-guest-advanced-pal; `x - (-1.0)`, which Godot 3 prints to GLSL as a
// decrement, as in tvout-tweaks; a loop declaring two variables, as crt-beans-rgb's), after crtforge's Godot 3 rewrite: accepted, and each runs as written.
TEST_CASE("godot3: loops without an initialiser, a step or a condition, an array declared from another or assigned a constructor, a negated subtrahend, a loop declaring two variables, run as written after the Godot 3 rewrite", "[godot3]") {
    const std::string code = godot::godot3::with_godot3_syntax(
        "shader_type canvas_item;\nvoid fragment()\n{\n    int i = 0;\n    float p[4];\n"
        "    for (; i < 4; i++)\n    {\n        p[i] = 0.125 * float(i + 1);\n    }\n"
        "    float sum = 0.0;\n    for (int j = 0; j < 4; )\n    {\n        sum += p[j];\n        j++;\n    }\n"
        "    int k = 0;\n    for (;;)\n    {\n        k++;\n        if (k >= 3)\n        {\n            break;\n        }\n    }\n"
        "    float q[4] = p;\n"
        "    float w[3] = float[](0.25, 0.5, 1.0);\n    if (sum > 1.0)\n    {\n        w = float[](0.5, max(0.25, 0.0), 0.75);\n    }\n"
        "    float m = 0.0625;\n"
        "    float acc = 0.0;\n    for (float s = 0.0, t = 1.0; s < 3.0; s += 1.0)\n    {\n        acc += t;\n        t *= 0.5;\n    }\n"
        "    COLOR = vec4((sum + acc) / 4.0, float(k) / 4.0, q[3] * w[2] - (-0.0625) - (-m), 1.0);\n}\n");
    CHECK_THAT(code, Contains("for (int crtforge_init0 = 0; i < 4; i++)"));
    CHECK_THAT(code, Contains("float q[4];"));
    CHECK_THAT(code, Contains("w[1] = max(0.25, 0.0);"));
    const Image out = render_ok(make_job(code, Image{}, 2, 2));
    CHECK_THAT(code, Contains("q[3] * w[2] + 0.0625 + m"));
    CHECK_THAT(code, Contains("float t = 1.0;\n    for (float s = 0.0; s < 3.0; s += 1.0)"));
    // sum: 0.125 + 0.25 + 0.375 + 0.5 = 1.25, acc: 1 + 0.5 + 0.25; k = 3; 0.5 * 0.75 + 0.125
    CHECK(out.pixel(0, 0) == P{0.75f, 0.75f, 0.5f, 1});
}
