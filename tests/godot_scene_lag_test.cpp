// Zero lag through the exported Godot scenes. A chain of viewports is known to show the previous
// frame's picture in Godot when a viewport is drawn before the one it reads (update order); the
// exported <preset>.tscn keeps its passes in drawing order so that every pass reads the frame it
// is in. A moving edge through every shipped multi-pass scene, in a real Godot 4 and a real
// Godot 3, must come out on the same frame it went in: each Godot frame matches Vulkan's render of
// that frame (validate's pipeline host), and not the frame before.
#include <catch2/catch.hpp>

#include <algorithm>

#include <fmt/format.h>

#include "crtforge/cache.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/validate/target_render.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

// A bright vertical edge that moves 9 source pixels a frame (so a frame's lag moves it by whole
// display pixels at any fit), over a dim ramp; 256 x 224, the NES frame the scenes are made for.
std::function<Result<Image>(int)> moving_edge() {
    return [](int frame) -> Result<Image> {
        constexpr int kWidth = 256, kHeight = 224;
        Image image = Image::make(kWidth, kHeight, {0, 0, 0, 1});
        const int edge = 40 + 9 * frame;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const float ramp = 0.1f + 0.2f * static_cast<float>(y) / kHeight;
                image.set_pixel(x, y, x < edge ? std::array<float, 4>{0.95f, 0.9f, 0.8f, 1} : std::array<float, 4>{ramp, ramp, ramp, 1});
            }
        return image;
    };
}

std::vector<Image> render(TargetRenderer& renderer, const Preset& preset, const std::vector<CompiledVariant>& passes, TargetId target,
                          const std::vector<TargetOutput>* outputs, const std::vector<int>& frames) {
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &passes;
    r.target = target;
    r.outputs = outputs;
    r.source = moving_edge();
    r.width = 320;
    r.height = 240;
    r.frames = frames;
    auto images = renderer.render_scene(r);
    INFO(target_info(target).name << ": " << (images.ok() ? std::string() : images.error().str()));
    REQUIRE(images.ok());
    return std::move(images).value();
}

// Godot's display is 8-bit, so clamped to 0..1 (the bloom adds past 1 where the edge is bright);
// Vulkan's is half float.
Image clamped(Image image) {
    for (float& v : image.rgba) v = std::clamp(v, 0.0f, 1.0f);
    return image;
}

double rmse(const Image& godot, const Image& vulkan) {
    auto m = compare_images(godot, clamped(vulkan));
    REQUIRE(m.ok());
    return m.value().rmse;
}

void check_no_lag(TargetId target) {
    const TemplateLibrary& lib = test::shipped_library();
    const std::vector<int> frames = {1, 2, 3, 4};
    TargetRenderer renderer;
    size_t scenes = 0;
    for (const Preset& preset : lib.presets()) {
        if (preset.single_pass()) continue;
        ++scenes;
        INFO(preset.name << " on " << target_info(target).name);
        auto passes = compile_scene(lib, preset, {}, Cache());
        REQUIRE(passes.ok());
        auto outputs = emit_scene(passes.value(), target, Cache());
        REQUIRE(outputs.ok());
        // Vulkan from frame 0, so frame f - 1 is there to compare with.
        const std::vector<Image> vulkan = render(renderer, preset, passes.value(), TargetId::Spirv, nullptr, {0, 1, 2, 3, 4});
        const std::vector<Image> godot = render(renderer, preset, passes.value(), target, &outputs.value(), frames);
        for (size_t i = 0; i < frames.size(); ++i) {
            const int f = frames[i];
            const double same = rmse(godot[i], vulkan[static_cast<size_t>(f)]);
            const double previous = rmse(godot[i], vulkan[static_cast<size_t>(f - 1)]);
            INFO("frame " << f << ": RMSE " << same << " against Vulkan's frame " << f << ", " << previous << " against frame " << f - 1);
            CHECK(same < 0.02);        // the 8-bit display and the chain's own rounding, far below a moved edge
            CHECK(same * 3 < previous);
        }
    }
    CHECK(scenes >= 2);  // super-win and atari-chain at least
}

}  // namespace

TEST_CASE("a moving edge comes out of every exported multi-pass scene on the frame it went in: real Godot 4", "[godot4][scene][lag]") {
    check_no_lag(TargetId::Godot4);
}

TEST_CASE("a moving edge comes out of every exported multi-pass scene on the frame it went in: real Godot 3", "[godot3][scene][lag]") {
    check_no_lag(TargetId::Godot3);
}
