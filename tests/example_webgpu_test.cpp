// The WebGPU example (examples/webgpu): crt-webgpu.mjs, driven only by what `crtforge export`
// writes (the .wgsl and manifest.json), must render a preset like the Vulkan render of the same
// preset. check.mjs runs the module in Node with Dawn (npm webgpu 0.6.2 from tools/wgsl-runner,
// OpenGL ES backend on llvmpipe); the module fills the uniform buffer itself from the manifest's
// byte layout and defaults, so a match proves the manifest is enough to drive the shader.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "crtforge/exporter.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/validate/target_render.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 120;
// Scenes show the NES-sized moving sprite at twice its size: nearest samples never land on a texel
// edge (where implementations may pick either texel).
constexpr int kSceneWidth = 2 * kPixelArtWidth, kSceneHeight = 2 * kPixelArtHeight;
constexpr double kTime = 0.5;
constexpr double kTolerance = 0.004;  // the project's RMSE tolerance

using test::slurp;

std::string last_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const auto nl = text.rfind('\n');
    return nl == std::string::npos ? text : text.substr(nl + 1);
}

Image read_raw(const std::string& path, int width, int height) {
    const std::string bytes = slurp(path);
    Image image = Image::make(width, height);
    REQUIRE(bytes.size() == image.rgba.size() * sizeof(float));
    std::memcpy(image.rgba.data(), bytes.data(), bytes.size());
    return image;
}

// `--export 'DIR'`: check.mjs reads an export's files; `--package 'APP'`: it imports the package.
std::string from_export(const std::string& dir) { return "--export '" + dir + "'"; }
std::string from_package(const std::string& app) { return "--package '" + app + "'"; }

// node examples/webgpu/check.mjs ...; fails the test with check.mjs's one-line error. Several
// inputs are the original at each frame of `frames` (written one after the other).
void run_check(const test::TempDir& tmp, const std::string& from, const std::string& preset, const std::vector<Image>& inputs,
               const std::string& output, const std::string& extra, int width = kWidth, int height = kHeight) {
    const std::string input_path = tmp / (preset + "-input.raw");
    {
        std::ofstream out(input_path, std::ios::binary | std::ios::trunc);
        for (const Image& input : inputs)
            out.write(reinterpret_cast<const char*>(input.rgba.data()), static_cast<std::streamsize>(input.rgba.size() * sizeof(float)));
        REQUIRE(out.good());
    }
    const Image& input = inputs.front();
    const std::string log = tmp / (preset + "-check.log"), err = tmp / (preset + "-check.err");
    const std::string cmd = "node '" + std::string(CRTFORGE_SOURCE_DIR) + "/examples/webgpu/check.mjs'" +
                            " " + from + " --preset '" + preset + "' --input '" + input_path + "'" +
                            " --input-width " + std::to_string(input.width) + " --input-height " + std::to_string(input.height) +
                            " --width " + std::to_string(width) + " --height " + std::to_string(height) + extra +
                            " --output '" + output + "'" + " >'" + log + "' 2>'" + err + "' </dev/null";
    const int status = std::system(cmd.c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    INFO("check.mjs: " << last_line(slurp(err)));  // dawn.node's start-up noise comes first
    REQUIRE(code == 0);
}

Image vulkan_render(const std::string& preset, const Image& input, double time = kTime) {
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
    r.time = time;
    auto image = renderer.render(r);
    INFO((image.ok() ? std::string() : image.error().str()));
    REQUIRE(image.ok());
    return std::move(image).value();
}

// Two GPU renders each within a golden's tolerance of the reference are within twice it of each
// other.
Tolerance doubled_golden_tolerance() {
    Tolerance tolerance = test::golden_plan_or_fail(test::shipped_library(), std::string(CRTFORGE_SOURCE_DIR) + "/golden").front().tolerance;
    tolerance.max_rmse *= 2;
    tolerance.max_tile_rmse *= 2;
    tolerance.outlier_threshold *= 2;
    return tolerance;
}

// Compares the frames check.mjs wrote (`prefix`<frame>.raw) with the Vulkan render of the preset's
// scene from the same inputs (one per frame, from frame 0).
void check_scene_frames_like_vulkan(TargetRenderer& renderer, const std::string& name, const std::vector<Image>& inputs,
                                    const std::string& prefix, const std::vector<int>& frames, const std::string& label) {
    const Preset* preset = test::shipped_library().find_preset(name);
    REQUIRE(preset != nullptr);
    auto compiled = compile_scene(test::shipped_library(), *preset, {}, Cache());
    REQUIRE(compiled.ok());
    SceneRenderRequest r;
    r.preset = preset;
    r.passes = &compiled.value();
    r.source = [&inputs](int frame) -> Result<Image> { return inputs.at(static_cast<size_t>(frame)); };
    r.width = kSceneWidth;
    r.height = kSceneHeight;
    r.frames = frames;
    auto vulkan = renderer.render_scene(r);
    INFO((vulkan.ok() ? std::string() : vulkan.error().str()));
    REQUIRE(vulkan.ok());
    const Tolerance tolerance = doubled_golden_tolerance();
    for (size_t i = 0; i < r.frames.size(); ++i) {
        const Image other = read_raw(prefix + std::to_string(r.frames[i]) + ".raw", kSceneWidth, kSceneHeight);
        auto metrics = compare_images(other, vulkan.value()[i]);
        REQUIRE(metrics.ok());
        const ImageMetrics& m = metrics.value();
        WARN(name << " " << label << " frame " << r.frames[i] << ": RMSE " << m.rmse << ", max |diff| " << m.max_abs << " at ("
                  << m.worst_x << ", " << m.worst_y << ")");
        auto verdict = judge(other, vulkan.value()[i], tolerance);  // HDR values included
        REQUIRE(verdict.ok());
        INFO(verdict.value().reason);
        CHECK(verdict.value().passed);
    }
}

// `crtforge export` of `presets` (comma list) to tmp/export, and an app folder tmp/app whose
// node_modules holds the export's npm/ package as `npm install ./export/npm` would (a symlink).
// Returns the app folder; `runner_file`: the npm file (under tools/wgsl-runner) the test needs.
std::string export_with_app(const test::TempDir& tmp, const std::string& targets, const std::string& presets, const char* runner_file) {
    const fs::path runner = fs::path(CRTFORGE_SOURCE_DIR) / "tools/wgsl-runner/node_modules";
    INFO("npm packages missing: run scripts/setup.sh");
    REQUIRE(fs::exists(runner / runner_file));
    const std::string export_dir = tmp / "export";
    const auto exported = test::run_crtforge("export --target " + targets + " --preset " + presets + " --out '" + export_dir + "'");
    INFO(exported.err);
    REQUIRE(exported.exit_code == 0);
    const std::string app = tmp / "app";
    fs::create_directories(fs::path(app) / "node_modules");
    fs::create_directory_symlink(fs::path(export_dir) / "npm", fs::path(app) / "node_modules/crtforge-presets");
    return app;
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

    // crt-pulse at 1e7 s (an f32 of which is 0.15 s off: 3 rad of phase): the module reduces time as the manifest says (reduceBy), like crtforge.
    for (const auto& [preset, time] : std::vector<std::pair<std::string, double>>{
             {"quiet-frame", kTime}, {"classic", kTime}, {"crt-shadow-mask", kTime}, {"crt-pulse", 1e7 + 0.15}}) {
        SECTION(preset) {
            const std::string output = tmp / (preset + "-webgpu.raw");
            run_check(tmp, from_export(export_dir), preset, {input.value()}, output, fmt::format(" --time {}", time));
            const Image webgpu = read_raw(output, kWidth, kHeight);
            const Image vulkan = vulkan_render(preset, input.value(), time);
            auto metrics = compare_images(webgpu, vulkan);
            REQUIRE(metrics.ok());
            const ImageMetrics& m = metrics.value();
            WARN(preset << ": RMSE " << m.rmse << ", max |diff| " << m.max_abs << " at (" << m.worst_x << ", "
                        << m.worst_y << "), PSNR " << m.psnr << " dB");
            CHECK(m.rmse <= kTolerance);
        }
    }
}

TEST_CASE("The WebGPU example runs whole scenes (passes, feedback, LUTs) like Vulkan", "[wgsl][example][scene]") {
    const fs::path webgpu_package = fs::path(CRTFORGE_SOURCE_DIR) / "tools/wgsl-runner/node_modules/webgpu/package.json";
    INFO("npm package 'webgpu' missing: run scripts/setup.sh");
    REQUIRE(fs::exists(webgpu_package));

    test::TempDir tmp;
    const std::string export_dir = tmp / "export";
    const std::vector<std::string> presets = {"super-win", "atari-chain", "atari-ntsc"};
    std::string args;
    for (const std::string& p : presets) args += " --preset " + p;
    const auto exported = test::run_crtforge("export --target wgsl --out '" + export_dir + "'" + args);
    INFO(exported.err);
    REQUIRE(exported.exit_code == 0);

    // A sprite crossing the NES-sized picture: super-win's trails read the previous frame.
    const std::vector<int> frames = {0, 1, 2, 3, 4};
    std::vector<Image> inputs;
    for (int f : frames) {
        auto input = make_test_input("moving_sprite", kPixelArtWidth, kPixelArtHeight, f);
        REQUIRE(input.ok());
        inputs.push_back(std::move(input.value()));
    }
    TargetRenderer renderer;
    for (const std::string& name : presets) {
        SECTION(name) {
            const std::string prefix = tmp / (name + "-frame-");
            run_check(tmp, from_export(export_dir), name, inputs, prefix, " --frames 0,1,2,3,4 --capture 1,4", kSceneWidth, kSceneHeight);
            check_scene_frames_like_vulkan(renderer, name, inputs, prefix, {1, 4}, "WebGPU");
        }
    }
}

// The export's npm/ folder is the package `crtforge-presets`: installed into an app (a symlink in
// its node_modules, as `npm install ./out/export/npm` makes), imported by name through its
// package.json, its loadCrtPreset() reads its own manifest, WGSL and LUT PNGs and renders exactly
// what the export's files give createCrtScene directly (which the tests above hold against Vulkan).
TEST_CASE("The export's npm package renders presets by name in Node, byte for byte like the export's files", "[wgsl][example][npm]") {
    test::TempDir tmp;
    const std::string app = export_with_app(tmp, "wgsl,glsl330", "classic,super-win,atari-ntsc", "webgpu/package.json");
    const std::string export_dir = tmp / "export";

    // The package is whole: its manifest names only WGSL files, and every file it names is inside it.
    const fs::path package = fs::path(export_dir) / "npm";
    const auto manifest = nlohmann::json::parse(slurp((package / "manifest.json").string()));
    CHECK(manifest["targets"] == nlohmann::json::array({"wgsl"}));
    size_t named = 0;
    for (const auto& [name, preset] : manifest["presets"].items()) {
        for (const auto& pass : preset["passes"]) {
            CHECK(pass["targets"].size() == 1);
            CHECK(fs::exists(package / pass["targets"]["wgsl"]["shader"].get<std::string>()));
            ++named;
        }
        if (preset.contains("luts"))
            for (const auto& [lut, entry] : preset["luts"].items()) CHECK(fs::exists(package / entry["file"].get<std::string>()));
    }
    CHECK(named == 1 + 6 + 1);
    const auto package_json = nlohmann::json::parse(slurp((package / "package.json").string()));
    CHECK(package_json["name"] == "crtforge-presets");
    CHECK(package_json["exports"]["."]["default"] == "./index.mjs");


    std::vector<Image> inputs;
    for (int f : {0, 1, 2}) {
        auto input = make_test_input("moving_sprite", kPixelArtWidth, kPixelArtHeight, f);
        REQUIRE(input.ok());
        inputs.push_back(std::move(input.value()));
    }
    for (const std::string preset : {"classic", "super-win", "atari-ntsc"}) {
        SECTION(preset) {
            const std::string direct = tmp / (preset + "-direct-"), packaged = tmp / (preset + "-package-");
            const std::string frames = " --frames 0,1,2 --capture 2 --time 0.5";
            run_check(tmp, from_export(export_dir), preset, inputs, direct, frames, kSceneWidth, kSceneHeight);
            run_check(tmp, from_package(app), preset, inputs, packaged, frames, kSceneWidth, kSceneHeight);
            const std::string a = slurp(direct + "2.raw"), b = slurp(packaged + "2.raw");
            CHECK(a.size() == size_t(kSceneWidth) * kSceneHeight * 16);
            CHECK(a == b);
            // Not a blank frame that would match anything.
            const Image picture = read_raw(packaged + "2.raw", kSceneWidth, kSceneHeight);
            CHECK(*std::max_element(picture.rgba.begin(), picture.rgba.end()) > 0.5f);
        }
    }
}

// The package's TypeScript declarations: an app using the API type-checks under --strict, and one
// that passes a param a string does not.
TEST_CASE("The npm package's .d.ts types an app's use of it", "[wgsl][example][npm]") {
    const fs::path runner = fs::path(CRTFORGE_SOURCE_DIR) / "tools/wgsl-runner/node_modules";
    test::TempDir tmp;
    const fs::path app = export_with_app(tmp, "wgsl", "classic", "typescript/bin/tsc");
    {
        std::ofstream config(app / "tsconfig.json");
        config << R"({ "compilerOptions": { "strict": true, "noEmit": true, "module": "nodenext",
  "moduleResolution": "nodenext", "target": "es2022", "lib": ["es2022", "dom"],
  "typeRoots": [")" << runner.string() << R"("], "types": ["@webgpu/types"] }, "files": ["app.mts"] })";
    }
    auto write_app = [&](const std::string& set_param) {
        std::ofstream out(app / "app.mts", std::ios::trunc);
        out << "import { loadCrtPreset, loadManifest, type Manifest, type CrtScene } from 'crtforge-presets';\n"
               "import { createThreeCrtPass, type ThreeWebGPURendererLike } from 'crtforge-presets/three';\n"
               "import { createPixiCrtPass, type PixiCrtPass, type PixiWebGPURendererLike } from 'crtforge-presets/pixi';\n"
               "import { createBabylonCrtPass, type BabylonCrtPass, type BabylonWebGPUEngineLike } from 'crtforge-presets/babylon';\n"
               "export async function three(renderer: ThreeWebGPURendererLike, game: { texture: object }, screen: { texture: object }) {\n"
               "  const pass = await createThreeCrtPass(renderer, 'classic', { format: 'rgba8unorm' });\n"
               "  await pass.render(game, screen, { time: 1.5 });\n"
               "}\n"
               "export async function babylon(engine: BabylonWebGPUEngineLike, game: object, screen: object) {\n"
               "  const pass: BabylonCrtPass = await createBabylonCrtPass(engine, 'classic', { format: 'rgba16float' });\n"
               "  await pass.render(game, screen, { fit: 'aspect' });\n"
               "}\n"
               "export async function pixi(renderer: PixiWebGPURendererLike, game: object, screen: object) {\n"
               "  const pass: PixiCrtPass = await createPixiCrtPass(renderer, 'classic');\n"
               "  await pass.render(game, screen, { frame: 3 });\n"
               "}\n"
               "export async function run(device: GPUDevice, source: GPUTexture, view: GPUTextureView): Promise<number> {\n"
               "  const manifest: Manifest = await loadManifest();\n"
               "  const crt: CrtScene = await loadCrtPreset(device, 'classic', { format: 'rgba8unorm' });\n"
            << "  " << set_param << "\n"
               "  const encoder = device.createCommandEncoder();\n"
               "  crt.encode(encoder, { source, target: view, width: 640, height: 480, time: 0.5 });\n"
               "  device.queue.submit([encoder.finish()]);\n"
               "  return (manifest.presets['classic'].passes[0].targets.wgsl.uniformBuffer?.members.length ?? 0) + crt.params().length;\n"
               "}\n";
    };
    const std::string tsc = "node '" + (runner / "typescript/bin/tsc").string() + "' -p '" + app.string() + "' 2>&1";
    write_app("crt.setParam('scanlineIntensity', 0.4);");
    auto good = test::run_command(tsc);
    INFO(good.out);
    CHECK(good.exit_code == 0);
    write_app("crt.setParam('scanlineIntensity', 'strong');");
    auto bad = test::run_command(tsc);
    INFO(bad.out);
    CHECK(bad.exit_code != 0);
    CHECK_THAT(bad.out, Catch::Contains("app.mts(20,") && Catch::Contains("'string'"));
}

// A web framework adapter of the package: the framework (pinned in tools/wgsl-runner) holds the
// 8-bit picture in its own texture, the adapter runs the preset on the framework's device into
// another; frame 2 of classic and super-win must match crtforge's Vulkan render of the same 8-bit
// picture. `flag` is check.mjs's switch (--three, --pixi, --babylon), `installed` a file of the
// framework's npm package.
namespace {

void check_framework_adapter(const std::string& flag, const char* installed, const std::string& framework) {
    test::TempDir tmp;
    const std::string app = export_with_app(tmp, "wgsl", "classic,super-win", installed);
    // The framework uploads 8-bit pictures: both renderers get the same 8-bit values.
    std::vector<Image> inputs;
    for (int f : {0, 1, 2}) {
        auto input = make_test_input("moving_sprite", kPixelArtWidth, kPixelArtHeight, f);
        REQUIRE(input.ok());
        for (float& v : input.value().rgba) v = std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
        inputs.push_back(std::move(input.value()));
    }
    TargetRenderer renderer;
    for (const std::string name : {"classic", "super-win"}) {
        INFO(name);
        const std::string prefix = tmp / (name + "-" + flag + "-");
        run_check(tmp, from_package(app) + " --" + flag + " on", name, inputs, prefix, " --frames 0,1,2 --capture 2",
                  kSceneWidth, kSceneHeight);
        check_scene_frames_like_vulkan(renderer, name, inputs, prefix, {2}, "through " + framework);
    }
}

}  // namespace

// three.js's WebGPURenderer on Dawn (GLES) draws the picture into a RenderTarget; the pass renders
// it into another.
TEST_CASE("The npm package's three.js adapter renders presets like Vulkan", "[wgsl][example][npm][three]") {
    check_framework_adapter("three", "three/package.json", "three.js");
}

// PixiJS v8's WebGPURenderer draws the picture as a Sprite into a RenderTexture; the pass renders it
// into another. On Dawn's Vulkan backend on SwiftShader: Pixi's shaders need a core adapter.
TEST_CASE("The npm package's PixiJS adapter renders presets like Vulkan", "[wgsl][example][npm][pixi]") {
    INFO("SwiftShader's Vulkan driver missing (Debian's chromium-common): run scripts/setup.sh");
    REQUIRE(fs::exists("/usr/lib/chromium/vk_swiftshader_icd.json"));
    check_framework_adapter("pixi", "pixi.js/package.json", "PixiJS");
}

// Babylon.js's WebGPUEngine uploads the picture as a RawTexture; the pass renders it into a
// RenderTargetTexture. On Dawn's Vulkan backend on SwiftShader, as PixiJS.
TEST_CASE("The npm package's Babylon.js adapter renders presets like Vulkan", "[wgsl][example][npm][babylon]") {
    INFO("SwiftShader's Vulkan driver missing (Debian's chromium-common): run scripts/setup.sh");
    REQUIRE(fs::exists("/usr/lib/chromium/vk_swiftshader_icd.json"));
    check_framework_adapter("babylon", "@babylonjs/core/package.json", "Babylon.js");
}

// RetroArch's default wrap, clamp_to_border, which WebGPU lacks: an imported two-pass .slangp whose
// passes read outside their textures, exported, rendered by the shipped host (which must sample
// clamp-to-edge where the manifest says the WGSL fades to the border) against crtforge's Vulkan
// render of the same .slangp.
TEST_CASE("The WebGPU example renders an imported .slangp's clamp_to_border like Vulkan", "[wgsl][example][retroarch]") {
    test::TempDir tmp;
    const std::string shader = test::slang_program(
        {"", "", "", "",
         "layout(set = 0, binding = 2) uniform sampler2D Source;\n"
         "void main() { FragColor = vec4(texture(Source, (vTexCoord - 0.5) * 1.35 + 0.5).rgb, 1.0); }\n"});
    std::ofstream(tmp / "zoom.slang") << shader;
    std::ofstream(tmp / "border.slangp") << "shaders = 2\nshader0 = zoom.slang\nfilter_linear0 = false\nscale_type0 = source\n"
                                             "shader1 = zoom.slang\nfilter_linear1 = true\n";
    const std::string slangp = tmp / "border.slangp", export_dir = tmp / "export";
    const auto exported = test::run_crtforge("export --target wgsl --out '" + export_dir + "' --preset '" + slangp + "'");
    INFO(exported.err);
    REQUIRE(exported.exit_code == 0);
    auto input = make_test_input("pixel_art", kPixelArtWidth, kPixelArtHeight, 0);
    REQUIRE(input.ok());
    const std::string prefix = tmp / "border-frame-";
    run_check(tmp, from_export(export_dir), "border", {input.value()}, prefix, " --frames 0 --capture 0", kSceneWidth, kSceneHeight);
    const Image webgpu = read_raw(prefix + "0.raw", kSceneWidth, kSceneHeight);

    const std::string vulkan_png = tmp / "vulkan.png";
    const auto rendered = test::run_crtforge(fmt::format("render --preset '{}' --input pixel_art --size {}x{} --output '{}'", slangp,
                                                         kSceneWidth, kSceneHeight, vulkan_png));
    INFO(rendered.err);
    REQUIRE(rendered.exit_code == 0);
    auto vulkan = read_image(vulkan_png);
    REQUIRE(vulkan.ok());
    // The corners are the border: transparent black under the display's opaque black.
    CHECK(vulkan.value().rgba[0] == 0.0f);
    auto metrics = compare_images(webgpu, vulkan.value());
    REQUIRE(metrics.ok());
    INFO("PSNR " << metrics.value().psnr << " dB, worst at (" << metrics.value().worst_x << ", " << metrics.value().worst_y << ")");
    CHECK(metrics.value().rmse <= kTolerance);
}
