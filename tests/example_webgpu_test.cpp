// The WebGPU example (examples/webgpu): crt-webgpu.mjs, driven only by what `crtforge export`
// writes (the .wgsl and manifest.json), must render a preset like the Vulkan render of the same
// preset. check.mjs runs the module in Node with Dawn (npm webgpu 0.6.2 from tools/wgsl-runner,
// OpenGL ES backend on llvmpipe); the module fills the uniform buffer itself from the manifest's
// byte layout and defaults, so a match proves the manifest is enough to drive the shader.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 120;
constexpr double kTime = 0.5;
constexpr double kTolerance = 0.004;  // the project's RMSE tolerance

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string last_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const auto nl = text.rfind('\n');
    return nl == std::string::npos ? text : text.substr(nl + 1);
}

void write_raw(const std::string& path, const Image& image) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(image.rgba.data()), static_cast<std::streamsize>(image.rgba.size() * sizeof(float)));
    REQUIRE(out.good());
}

Image read_raw(const std::string& path, int width, int height) {
    const std::string bytes = slurp(path);
    Image image = Image::make(width, height);
    REQUIRE(bytes.size() == image.rgba.size() * sizeof(float));
    std::memcpy(image.rgba.data(), bytes.data(), bytes.size());
    return image;
}

// node examples/webgpu/check.mjs ...; fails the test with check.mjs's one-line error.
void run_check(const test::TempDir& tmp, const std::string& export_dir, const std::string& preset, const Image& input,
               const std::string& output) {
    const std::string input_path = tmp / (preset + "-input.raw");
    write_raw(input_path, input);
    const std::string log = tmp / (preset + "-check.log"), err = tmp / (preset + "-check.err");
    const std::string cmd = "node '" + std::string(CRTFORGE_SOURCE_DIR) + "/examples/webgpu/check.mjs'" +
                            " --export '" + export_dir + "' --preset '" + preset + "' --input '" + input_path + "'" +
                            " --input-width " + std::to_string(input.width) + " --input-height " + std::to_string(input.height) +
                            " --width " + std::to_string(kWidth) + " --height " + std::to_string(kHeight) +
                            " --time " + std::to_string(kTime) + " --output '" + output + "'" +
                            " >'" + log + "' 2>'" + err + "' </dev/null";
    const int status = std::system(cmd.c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    INFO("check.mjs: " << last_line(slurp(err)));  // dawn.node's start-up noise comes first
    REQUIRE(code == 0);
}

Image vulkan_render(const std::string& preset, const Image& input) {
    static TargetRenderer renderer;
    const CompiledVariant compiled = test::compile_or_fail(test::shipped_library(), preset);
    const Preset* p = test::shipped_library().find_preset(preset);
    REQUIRE(p != nullptr);
    TargetRenderRequest r;
    r.compiled = &compiled;
    r.target = TargetId::Spirv;
    r.input = input;
    r.filter = p->filter == Filter::Nearest ? SamplerFilter::Nearest : SamplerFilter::Linear;
    r.width = kWidth;
    r.height = kHeight;
    r.time = kTime;
    auto image = renderer.render(r);
    INFO((image.ok() ? std::string() : image.error().str()));
    REQUIRE(image.ok());
    return std::move(image).value();
}

}  // namespace

TEST_CASE("The WebGPU example module renders exported presets like Vulkan", "[wgsl][example]") {
    const fs::path webgpu_package = fs::path(CRTFORGE_SOURCE_DIR) / "tools/wgsl-runner/node_modules/webgpu/package.json";
    INFO("npm package 'webgpu' missing: run scripts/setup.sh");
    REQUIRE(fs::exists(webgpu_package));

    test::TempDir tmp;
    const std::string export_dir = tmp / "export";
    const auto exported = test::run_crtforge("export --out '" + export_dir + "'");
    INFO(exported.err);
    REQUIRE(exported.exit_code == 0);

    // pixel_art at its native NES size, as `crtforge render --input pixel_art` uses it.
    auto input = make_test_input("pixel_art", kPixelArtWidth, kPixelArtHeight);
    REQUIRE(input.ok());

    for (const std::string preset : {"quiet-frame", "classic", "crt-shadow-mask"}) {
        SECTION(preset) {
            const std::string output = tmp / (preset + "-webgpu.raw");
            run_check(tmp, export_dir, preset, input.value(), output);
            const Image webgpu = read_raw(output, kWidth, kHeight);
            const Image vulkan = vulkan_render(preset, input.value());
            auto metrics = compare_images(webgpu, vulkan);
            REQUIRE(metrics.ok());
            const ImageMetrics& m = metrics.value();
            WARN(preset << ": RMSE " << m.rmse << ", max |diff| " << m.max_abs << " at (" << m.worst_x << ", "
                        << m.worst_y << "), PSNR " << m.psnr << " dB");
            CHECK(m.rmse <= kTolerance);
        }
    }
}
