// The Dawn engine: hand-written WGSL compiled and rendered by Dawn (npm webgpu 0.6.2, OpenGL ES
// backend on Mesa llvmpipe) through tools/wgsl-runner. One engine is shared by the cases of a
// process (ctest runs each case in its own process, so each pays one start-up, ~0.3 s). The
// conventions pinned here (position and texture origin top-left, exact rgba32float input for
// Nearest, half-float read-back) are the ones the WGSL emitter relies on.
#include <catch2/catch.hpp>

#include <dirent.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "crtforge/runtime/dawn_engine.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
using Catch::Matchers::Contains;
using P = std::array<float, 4>;

DawnEngine& engine() {
    static std::unique_ptr<DawnEngine> shared = [] {
        auto created = DawnEngine::create();
        INFO((created.ok() ? std::string() : created.error().str()));
        REQUIRE(created.ok());
        return std::move(created).value();
    }();
    return *shared;
}

// A full-screen triangle from vertex_index, shared by every module below.
const std::string kVertex = R"(
@vertex fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
  let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
  return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}
)";

const std::string kSampling = R"(
@group(0) @binding(1) var t: texture_2d<f32>;
@group(0) @binding(2) var s: sampler;
@fragment fn fs_main(@builtin(position) p: vec4f) -> @location(0) vec4f {
  return textureSample(t, s, p.xy / vec2f(OUT_W, OUT_H));
}
)";

std::string sampling_module(int width, int height) {
    std::string code = kVertex + kSampling;
    code.replace(code.find("OUT_W"), 5, std::to_string(width) + ".0");
    code.replace(code.find("OUT_H"), 5, std::to_string(height) + ".0");
    return code;
}

DawnJob make_job(std::string wgsl, int width, int height, Image input = {},
                 SamplerFilter filter = SamplerFilter::Nearest) {
    auto job = test::frame_job<DawnJob>(std::move(input), width, height, OutputFormat::Rgba16Float, filter);
    job.wgsl = std::move(wgsl);
    return job;
}

Image render_ok(const DawnJob& job) {
    return test::require_image(engine().render(job), job.width, job.height);
}

Diagnostic render_error(DawnEngine& e, const DawnJob& job) {
    auto image = e.render(job);
    REQUIRE_FALSE(image.ok());
    const Diagnostic& error = image.error();
    CHECK(error.str().find('\n') == std::string::npos);  // one line
    return error;
}

Diagnostic render_error(const DawnJob& job) { return render_error(engine(), job); }

// Within half-float precision (11 significant bits).
bool near_half(float got, float want) { return std::fabs(got - want) <= std::fabs(want) * 0x1p-10f + 1e-7f; }

bool near_half(const P& got, const P& want) {
    for (std::size_t c = 0; c < 4; ++c)
        if (!near_half(got[c], want[c])) return false;
    return true;
}

std::vector<uint8_t> float_bytes(std::vector<float> values) {
    std::vector<uint8_t> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

// The runner processes this test process started (children running runner.mjs).
std::set<pid_t> runner_children() {
    std::set<pid_t> pids;
    DIR* proc = ::opendir("/proc");
    if (!proc) return pids;
    while (dirent* entry = ::readdir(proc)) {
        const pid_t pid = static_cast<pid_t>(std::atoi(entry->d_name));
        if (pid <= 0) continue;
        std::ifstream stat("/proc/" + std::string(entry->d_name) + "/stat");
        std::string line;
        std::getline(stat, line);
        const std::size_t close = line.rfind(')');
        char state = 0;
        int ppid = 0;
        if (close == std::string::npos || std::sscanf(line.c_str() + close + 1, " %c %d", &state, &ppid) != 2 ||
            ppid != ::getpid() || state == 'Z')
            continue;
        std::ifstream cmdline("/proc/" + std::string(entry->d_name) + "/cmdline");
        const std::string args((std::istreambuf_iterator<char>(cmdline)), std::istreambuf_iterator<char>());
        if (args.find("runner.mjs") != std::string::npos) pids.insert(pid);
    }
    ::closedir(proc);
    return pids;
}

}  // namespace

TEST_CASE("dawn: the engine starts on an adapter and describes it", "[runtime][dawn]") {
    const std::string description = engine().adapter_description();
    INFO(description);
    CHECK_THAT(description, Contains("Dawn (npm webgpu 0.6.2)"));
    CHECK_THAT(description, Contains("opengles"));
}

TEST_CASE("dawn: compile reports errors with their line, warnings, and nothing for clean code", "[runtime][dawn]") {
    auto clean = engine().compile(kVertex + "@fragment fn fs_main() -> @location(0) vec4f { return vec4f(1.0); }\n");
    REQUIRE(clean.ok());
    CHECK(clean.value().empty());

    // Line 3 lacks the ';' after the return value (the module starts with a newline).
    const std::string broken = "\n@fragment fn fs_main() -> @location(0) vec4f {\n  return vec4f(1.0)\n}\n";
    auto errors = engine().compile(broken);
    REQUIRE(errors.ok());
    REQUIRE_FALSE(errors.value().empty());
    const WgslMessage& first = errors.value().front();
    CHECK(first.type == "error");
    CHECK(first.line == 4);  // Tint reports the missing ';' where the next token starts: the '}'
    CHECK(first.column == 1);
    CHECK_THAT(first.text, Contains("expected ';'"));

    // Dawn warns about unreachable code (it has no unused-variable warning).
    const std::string unreachable = kVertex +
                                    "@fragment fn fs_main() -> @location(0) vec4f {\n"
                                    "  return vec4f(1.0);\n"
                                    "  let late = 2.0;\n"
                                    "}\n";
    auto warned = engine().compile(unreachable);
    REQUIRE(warned.ok());
    REQUIRE(warned.value().size() == 1);
    const WgslMessage& warning = warned.value().front();
    CHECK(warning.type == "warning");
    CHECK(warning.line == 8);  // kVertex is 5 lines, the fragment's `let` is the 3rd of its own
    CHECK(warning.column == 3);
    CHECK_THAT(warning.text, Contains("unreachable"));

    // A warning does not fail a render.
    DawnJob job = make_job(unreachable, 1, 1);
    job.uses_texture = false;
    const Image out = render_ok(job);
    CHECK(out.pixel(0, 0) == P{1, 1, 1, 1});
}

TEST_CASE("dawn: @builtin(position) is in pixels from the top-left, row 0 is the top row", "[runtime][dawn]") {
    const std::string code = kVertex + R"(
@fragment fn fs_main(@builtin(position) p: vec4f) -> @location(0) vec4f {
  return vec4f(p.x / 8.0, p.y / 4.0, 0.25, 1.0);
}
)";
    DawnJob job = make_job(code, 8, 4);
    job.uses_texture = false;
    const Image out = render_ok(job);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 8; ++x) {
            INFO("pixel " << x << ", " << y);
            CHECK(out.pixel(x, y) == P{(x + 0.5f) / 8.0f, (y + 0.5f) / 4.0f, 0.25f, 1.0f});
        }
    }
}

TEST_CASE("dawn: uniform buffer values reach the shader, and a short buffer is refused", "[runtime][dawn]") {
    const std::string code = kVertex + R"(
struct Params { tint: vec4f, gain: f32, }
@group(0) @binding(0) var<uniform> params: Params;
@fragment fn fs_main() -> @location(0) vec4f {
  return params.tint * params.gain;
}
)";
    DawnJob job = make_job(code, 2, 2);
    job.uses_texture = false;
    job.uniform_data = float_bytes({1.25f, -2.5f, 100.0f, 0.5f, 2.0f, 0, 0, 0});
    const Image out = render_ok(job);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) CHECK(out.pixel(x, y) == P{2.5f, -5.0f, 200.0f, 1.0f});

    job.uniform_data = float_bytes({1.0f, 1.0f, 1.0f, 1.0f});  // 16 of the block's 32 bytes
    const Diagnostic short_buffer = render_error(job);
    CHECK(short_buffer.kind == ErrorKind::Validation);
    CHECK_THAT(short_buffer.message, Contains("Dawn rejected the render"));

    job.uniform_data.clear();  // the shader uses binding 0 but the job binds nothing there
    const Diagnostic missing = render_error(job);
    CHECK(missing.kind == ErrorKind::Validation);
}

TEST_CASE("dawn: nearest sampling returns the input texels, HDR and negative values intact", "[runtime][dawn]") {
    Image input = Image::make(3, 2);
    input.set_pixel(0, 0, {1, 0, 0, 1});
    input.set_pixel(1, 0, {3.5f, 0.25f, -0.5f, 1});
    input.set_pixel(2, 0, {0.3f, 0.6f, 0.9f, 0.7f});
    input.set_pixel(0, 1, {-2.0f, 10.0f, 0.001f, 0});
    input.set_pixel(1, 1, {0, 0, 1, 1});
    input.set_pixel(2, 1, {1000.0f, 0.125f, 0.5f, 0.5f});
    const Image out = render_ok(make_job(sampling_module(3, 2), 3, 2, input, SamplerFilter::Nearest));
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 3; ++x) {
            INFO("pixel " << x << ", " << y << ": got " << out.pixel(x, y)[0] << " " << out.pixel(x, y)[1] << " "
                          << out.pixel(x, y)[2] << " " << out.pixel(x, y)[3]);
            CHECK(near_half(out.pixel(x, y), input.pixel(x, y)));
        }
    }
    CHECK(out.pixel(1, 0) == P{3.5f, 0.25f, -0.5f, 1});  // exact where the value is a half

    // 2x upscale with nearest repeats each texel.
    const Image up = render_ok(make_job(sampling_module(6, 4), 6, 4, input, SamplerFilter::Nearest));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) CHECK(near_half(up.pixel(x, y), input.pixel(x / 2, y / 2)));
}

TEST_CASE("dawn: linear sampling averages at a half-texel offset", "[runtime][dawn]") {
    Image input = Image::make(2, 1);
    input.set_pixel(0, 0, {0.0f, 1.0f, 3.5f, 1});
    input.set_pixel(1, 0, {1.0f, -1.0f, 0.5f, 1});
    // 4 pixels over 2 texels: centres at texel coordinates -0.25, 0.25, 0.75, 1.25 (clamped).
    const Image out = render_ok(make_job(sampling_module(4, 1), 4, 1, input, SamplerFilter::Linear));
    CHECK(near_half(out.pixel(0, 0), P{0.0f, 1.0f, 3.5f, 1}));
    CHECK(near_half(out.pixel(1, 0), P{0.25f, 0.5f, 2.75f, 1}));
    CHECK(near_half(out.pixel(2, 0), P{0.75f, -0.5f, 1.25f, 1}));
    CHECK(near_half(out.pixel(3, 0), P{1.0f, -1.0f, 0.5f, 1}));

    // One pixel sampling the middle of the 2x1 texture: the exact average.
    const Image middle = render_ok(make_job(sampling_module(1, 1), 1, 1, input, SamplerFilter::Linear));
    CHECK(near_half(middle.pixel(0, 0), P{0.5f, 0.0f, 2.0f, 1}));
}

TEST_CASE("dawn: an empty input binds a 1x1 transparent-black texture", "[runtime][dawn]") {
    const Image out = render_ok(make_job(sampling_module(2, 2), 2, 2));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) CHECK(out.pixel(x, y) == P{0, 0, 0, 0});
}

TEST_CASE("dawn: 8-bit outputs read back as byte / 255, sRGB decoded", "[runtime][dawn]") {
    const std::string code = kVertex + R"(
@fragment fn fs_main() -> @location(0) vec4f { return vec4f(0.5, 2.0, -1.0, 0.2); }
)";
    DawnJob job = make_job(code, 1, 1);
    job.uses_texture = false;
    job.format = OutputFormat::Rgba8Unorm;
    const Image unorm = render_ok(job);
    CHECK(unorm.pixel(0, 0) == P{128 / 255.0f, 1, 0, 51 / 255.0f});
    job.format = OutputFormat::Rgba8Srgb;
    const Image srgb = render_ok(job);
    CHECK(std::fabs(srgb.pixel(0, 0)[0] - 0.5f) < 0.005f);  // 0.5 -> byte 188 -> 0.5029
    CHECK(srgb.pixel(0, 0)[1] == 1.0f);
    CHECK(srgb.pixel(0, 0)[2] == 0.0f);
    CHECK(srgb.pixel(0, 0)[3] == 51 / 255.0f);  // alpha is linear
}

TEST_CASE("dawn: bad jobs are input errors before any work", "[runtime][dawn]") {
    const std::string code = sampling_module(2, 2);
    Diagnostic error = render_error(make_job(code, 0, 2));
    CHECK(error.kind == ErrorKind::Input);
    CHECK(error.field == "job.width");
    error = render_error(make_job(code, 2, 16385));
    CHECK(error.field == "job.height");
    error = render_error(make_job(code, -1, -1));
    CHECK(error.field == "job.width");

    Image broken = Image::make(2, 2);
    broken.rgba.pop_back();
    error = render_error(make_job(code, 2, 2, broken));
    CHECK(error.kind == ErrorKind::Input);
    CHECK(error.field == "job.input");

    error = render_error(make_job("", 2, 2));
    CHECK(error.field == "job.wgsl");

    DawnJob clash = make_job(code, 2, 2);
    clash.sampler_binding = clash.texture_binding;
    error = render_error(clash);
    CHECK(error.field == "job.sampler_binding");

    // The engine still renders afterwards.
    CHECK(render_ok(make_job(code, 2, 2)).pixel(0, 0) == P{0, 0, 0, 0});
}

TEST_CASE("dawn: a module that does not compile fails the render with its line", "[runtime][dawn]") {
    const std::string code = kVertex + "@fragment fn fs_main() -> @location(0) vec4f {\n  return undefined_thing;\n}\n";
    const Diagnostic error = render_error(make_job(code, 2, 2));
    CHECK(error.kind == ErrorKind::Validation);
    CHECK(error.line == 7);
    CHECK(error.column == 10);
    CHECK_THAT(error.message, Contains("Dawn rejected the WGSL: 7:10:"));
    CHECK_THAT(error.message, Contains("undefined_thing"));

    DawnJob wrong_entry = make_job(sampling_module(2, 2), 2, 2);
    wrong_entry.fragment_entry = "no_such_entry";
    const Diagnostic entry = render_error(wrong_entry);
    CHECK(entry.kind == ErrorKind::Validation);
    CHECK_THAT(entry.message, Contains("no_such_entry"));
}

TEST_CASE("dawn: a runner that dies fails one call, and the next call restarts it", "[runtime][dawn]") {
    const std::set<pid_t> before = runner_children();  // e.g. the shared engine's runner: not ours to kill
    auto created = DawnEngine::create();
    REQUIRE(created.ok());
    DawnEngine& own = *created.value();
    DawnJob job = make_job(sampling_module(2, 2), 2, 2);
    REQUIRE(own.render(job).ok());

    int killed = 0;
    for (pid_t pid : runner_children()) {
        if (before.count(pid)) continue;
        ::kill(pid, SIGKILL);
        ++killed;
    }
    REQUIRE(killed == 1);

    const Diagnostic died = render_error(own, job);
    INFO(died.str());
    CHECK(died.kind == ErrorKind::Validation);
    CHECK_THAT(died.message, Contains("the Dawn runner exited during render (signal 9"));
    auto again = own.render(job);
    INFO((again.ok() ? std::string() : again.error().str()));
    CHECK(again.ok());
    CHECK(runner_children().size() == before.size() + 1);
    created.value().reset();  // the destructor ends and reaps its runner
    CHECK(runner_children() == before);
}

TEST_CASE("dawn: threads sharing one engine each get their own result", "[runtime][dawn]") {
    const std::string code = kVertex + R"(
@group(0) @binding(0) var<uniform> value: vec4f;
@fragment fn fs_main() -> @location(0) vec4f { return value; }
)";
    std::vector<std::thread> threads;
    std::vector<int> failures(4, 0);
    for (int t = 0; t < 4; ++t) {
        threads.emplace_back([&, t] {
            for (int i = 0; i < 3; ++i) {
                DawnJob job = make_job(code, 3, 2);
                job.uses_texture = false;
                const float v = static_cast<float>(t * 10 + i);
                job.uniform_data = float_bytes({v, -v, 0.5f, 1});
                auto image = engine().render(job);
                if (!image.ok() || image.value().pixel(2, 1) != P{v, -v, 0.5f, 1}) ++failures[t];
            }
        });
    }
    for (std::thread& thread : threads) thread.join();
    CHECK(failures == std::vector<int>(4, 0));
}

// ---- several textures, wrap modes, viewport and clear colour -------------------------------------

namespace {

// A full-screen triangle that also passes the texture coordinate on, (0, 0) at the top-left of
// the viewport, as the generated vertex shaders do.
const std::string kVertexUv = R"(
struct VOut { @builtin(position) pos: vec4f, @location(0) uv: vec2f, }
@vertex fn vs_main(@builtin(vertex_index) i: u32) -> VOut {
  let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
  var o: VOut;
  o.pos = vec4f(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
  o.uv = uv;
  return o;
}
)";

// A width x 1 image whose red channel holds `values` (the other channels 0, alpha 1).
Image row_of(std::initializer_list<float> values) {
    Image image = Image::make(static_cast<int>(values.size()), 1);
    int x = 0;
    for (float v : values) image.set_pixel(x++, 0, {v, 0.0f, 0.0f, 1.0f});
    return image;
}

TextureInput texture_input(uint32_t binding, uint32_t sampler_binding, Image image, SamplerFilter filter,
                           WrapMode wrap = WrapMode::ClampToEdge) {
    TextureInput texture;
    texture.binding = binding;
    texture.sampler_binding = sampler_binding;
    texture.image = std::move(image);
    texture.filter = filter;
    texture.wrap = wrap;
    return texture;
}

}  // namespace

TEST_CASE("dawn: extra textures are read at their own bindings with their own filters", "[runtime][dawn]") {
    const std::string code = kVertexUv + R"(
@group(0) @binding(1) var source: texture_2d<f32>;
@group(0) @binding(2) var source_sampler: sampler;
@group(0) @binding(3) var texA: texture_2d<f32>;
@group(0) @binding(4) var samplerA: sampler;
@group(0) @binding(6) var texB: texture_2d<f32>;
@group(0) @binding(5) var samplerB: sampler;
@fragment fn fs_main(@location(0) uv: vec2f) -> @location(0) vec4f {
  return vec4f(textureSample(texA, samplerA, uv).r, textureSample(texB, samplerB, uv).r,
               textureSample(source, source_sampler, uv).r, 1.0);
}
)";
    // Two output columns sample u = 1/4 and 3/4: the centres of texA's two texels (nearest), and
    // exactly halfway between texB's texels 0|1 and 2|3 (linear: their averages).
    DawnJob job = make_job(code, 2, 2, Image::make(1, 1, {0.125f, 0, 0, 1}));
    job.textures.push_back(texture_input(3, 4, row_of({0.25f, 0.75f}), SamplerFilter::Nearest));
    job.textures.push_back(texture_input(6, 5, row_of({0.0f, 1.0f, 0.5f, 0.25f}), SamplerFilter::Linear));
    const Image out = render_ok(job);
    for (int y = 0; y < 2; ++y) {
        INFO("row " << y);
        CHECK(out.pixel(0, y)[0] == 0.25f);
        CHECK(out.pixel(1, y)[0] == 0.75f);
        CHECK(out.pixel(0, y)[1] == Approx(0.5).margin(1.0 / 256));
        CHECK(out.pixel(1, y)[1] == Approx(0.375).margin(1.0 / 256));
        CHECK(out.pixel(0, y)[2] == 0.125f);  // the input is still at texture_binding
        CHECK(out.pixel(1, y)[2] == 0.125f);
    }
}

TEST_CASE("dawn: each wrap mode returns its texel outside 0..1, for the input and an extra texture",
          "[runtime][dawn]") {
    // Column 0 samples u = -0.375, column 1 u = 1.375: the centres of texels -2 and 5 of a 4-texel
    // row (texel centres, not the edges at -0.25 / 1.25, where nearest may round either way).
    const std::string code = kVertexUv + R"(
@group(0) @binding(1) var source: texture_2d<f32>;
@group(0) @binding(2) var source_sampler: sampler;
@group(0) @binding(3) var extra: texture_2d<f32>;
@group(0) @binding(4) var extra_sampler: sampler;
@fragment fn fs_main(@location(0) uv: vec2f) -> @location(0) vec4f {
  let at = vec2f(select(1.375, -0.375, uv.x < 0.5), 0.5);
  return vec4f(textureSample(source, source_sampler, at).r, textureSample(extra, extra_sampler, at).r, 0.0, 1.0);
}
)";
    const Image texels = row_of({0.125f, 0.25f, 0.5f, 1.0f});
    struct Case {
        WrapMode wrap;
        float left, right;
    };
    const Case cases[] = {{WrapMode::ClampToEdge, 0.125f, 1.0f},     // texel 0 / texel 3
                          {WrapMode::Repeat, 0.5f, 0.25f},           // -2 -> 2, 5 -> 1
                          {WrapMode::MirroredRepeat, 0.25f, 0.5f}};  // -2 -> 1, 5 -> 2
    DawnJob job = make_job(code, 2, 1, texels, SamplerFilter::Nearest);
    for (const Case& c : cases) {
        INFO("wrap mode " << static_cast<int>(c.wrap));
        job.wrap = c.wrap;
        job.textures = {texture_input(3, 4, texels, SamplerFilter::Nearest, c.wrap)};
        const Image out = render_ok(job);
        CHECK(out.pixel(0, 0) == P{c.left, c.left, 0.0f, 1.0f});
        CHECK(out.pixel(1, 0) == P{c.right, c.right, 0.0f, 1.0f});
    }
}

TEST_CASE("dawn: a viewport draws a pasted full render and keeps the clear colour around it", "[runtime][dawn]") {
    const std::string code = kVertexUv + R"(
@group(0) @binding(1) var source: texture_2d<f32>;
@group(0) @binding(2) var source_sampler: sampler;
@fragment fn fs_main(@location(0) uv: vec2f) -> @location(0) vec4f {
  return vec4f(textureSample(source, source_sampler, uv).rg, uv);
}
)";
    Image input = Image::make(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) input.set_pixel(x, y, {(x + 1) / 8.0f, (y + 1) / 4.0f, 0.0f, 1.0f});
    const Image full = render_ok(make_job(code, 8, 4, input));

    DawnJob job = make_job(code, 16, 8, input);
    job.viewport = {4, 2, 8, 4};
    job.clear_color = {0, 0, 0, 1};
    const Image out = render_ok(job);
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
    const Image srgb = render_ok(job);
    CHECK(srgb.pixel(15, 7)[0] == Approx(0.5).margin(0.004));
    CHECK(srgb.pixel(15, 7)[1] == Approx(0.25).margin(0.004));
}

TEST_CASE("dawn: bad textures, viewports and clear colours are input errors", "[runtime][dawn]") {
    const std::string code = kVertexUv + R"(
@group(0) @binding(1) var source: texture_2d<f32>;
@group(0) @binding(2) var source_sampler: sampler;
@group(0) @binding(3) var lut: texture_2d<f32>;
@group(0) @binding(4) var lut_sampler: sampler;
@fragment fn fs_main(@location(0) uv: vec2f) -> @location(0) vec4f {
  return textureSample(source, source_sampler, uv) + textureSample(lut, lut_sampler, uv);
}
)";
    DawnJob good = make_job(code, 16, 8, Image::make(2, 2, {0.25f, 0, 0, 1}));
    good.textures = {texture_input(3, 4, Image::make(2, 1, {0.5f, 0, 0, 0}), SamplerFilter::Linear)};
    auto expect = [](const DawnJob& job, const std::string& field) {
        const Diagnostic error = render_error(job);
        INFO(error.str());
        CHECK(error.kind == ErrorKind::Input);
        CHECK(error.field == field);
    };
    DawnJob job = good;
    job.viewport = {12, 2, 8, 4};  // 12 + 8 > 16
    expect(job, "job.viewport");
    job.viewport = {0, 0, 0, 4};  // a zero side
    expect(job, "job.viewport");
    job.viewport = {4, 2, -8, 4};
    expect(job, "job.viewport");

    job = good;
    job.textures.push_back(texture_input(3, 7, Image{}, SamplerFilter::Nearest));  // texture at texture 0's binding
    expect(job, "job.textures[1].binding");
    job = good;
    job.textures[0].sampler_binding = 2;  // the input's sampler
    expect(job, "job.textures[0].sampler_binding");
    job = good;
    job.textures[0].binding = 0;
    job.uniform_data = float_bytes({1.0f, 2.0f, 3.0f, 4.0f});  // the uniform buffer's
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
    job.clear_color[3] = -INFINITY;
    expect(job, "job.clear_color");

    const Image out = render_ok(good);  // the engine carries on
    CHECK(out.pixel(0, 0)[0] == 0.75f);
}
