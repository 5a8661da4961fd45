// Scenes: the pass graph's checks (cycles, unknown sources, unbound textures), the geometry every
// host shares, and the two behaviours the documents' scenes rest on, measured on Vulkan and the
// fp64 reference alike: feedback really reads the previous frame (Super Win the Game's trails
// decay by trailBlend * trailTint per frame), and the Atari palette pass outputs palette colours
// only, dithered by the article's 4x4 Bayer matrix.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "crtforge/exporter.hpp"
#include "crtforge/luts.hpp"
#include "crtforge/preset.hpp"
#include "crtforge/quality_tiers.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/scene.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/validate/target_render.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;

Result<Preset> resolve_texts(const std::vector<std::pair<std::string, std::string>>& files, const std::string& name) {
    return test::resolve_preset_texts(files, name);
}

Preset resolve_or_fail(const std::string& text, const std::string& name) {
    auto p = resolve_texts({{name + ".toml", text}}, name);
    INFO((p.ok() ? std::string() : p.error().str()));
    REQUIRE(p.ok());
    return std::move(p).value();
}

// The display images of `frames` of a scene, from Vulkan (lavapipe) and from the fp64 reference.
struct SceneRenders {
    std::vector<Image> vulkan, reference;
};

SceneRenders render_both(const Preset& preset, const std::function<Result<Image>(int)>& source, int width, int height,
                         const std::vector<int>& frames, const std::map<std::string, Value>& overrides = {},
                         OutputFormat display = OutputFormat::Rgba16Float) {
    const TemplateLibrary& lib = test::shipped_library();
    auto compiled = compile_scene(lib, preset, {}, Cache());
    INFO((compiled.ok() ? std::string() : compiled.error().str()));
    REQUIRE(compiled.ok());
    static TargetRenderer renderer;
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &compiled.value();
    r.source = source;
    r.width = width;
    r.height = height;
    r.frames = frames;
    r.overrides = overrides;
    r.format = display;
    auto vulkan = renderer.render_scene(r);
    INFO((vulkan.ok() ? std::string() : vulkan.error().str()));
    REQUIRE(vulkan.ok());
    ReferenceSceneJob job;
    job.library = &lib;
    job.preset = &preset;
    job.source = source;
    job.width = width;
    job.height = height;
    job.frames = frames;
    job.overrides = overrides;
    auto reference = render_reference_scene(job);
    INFO((reference.ok() ? std::string() : reference.error().str()));
    REQUIRE(reference.ok());
    return {std::move(vulkan).value(), std::move(reference).value()};
}

// One pass holding Super Win the Game's trails (blend 0.6, tint 1, 0.7, 0.45), its feedback its
// own previous output.
Preset trail_probe() {
    return resolve_or_fail("name = \"trail-probe\"\ndoc = \"d\"\n[[pass]]\nalias = \"nes\"\nscale_type = \"source\"\n"
                           "filter = \"nearest\"\n[pass.textures]\nfeedback = \"nes@previous\"\n"
                           "[pass.stages.trails]\ntrailBlend = 0.6\ntrailTint = [1.0, 0.7, 0.45]\n",
                           "trail-probe");
}

// A black square picture with a white bar `bar` rows high across it, `bar` rows lower each frame.
std::function<Result<Image>(int)> falling_bar(int size, int bar) {
    return [size, bar](int frame) -> Result<Image> {
        Image image = Image::make(size, size, {0, 0, 0, 1});
        for (int y = frame * bar; y < (frame + 1) * bar && y < size; ++y)
            for (int x = 0; x < size; ++x) image.set_pixel(x, y, {1, 1, 1, 1});
        return image;
    };
}

}  // namespace

TEST_CASE("the pass graph: cycles, unknown sources and unbound textures are file:line errors", "[scene][errors]") {
    const std::string head = "name = \"p\"\ndoc = \"d\"\n";
    SECTION("two passes reading each other this frame") {
        auto p = resolve_texts({{"p.toml", head +
                                               "[[pass]]\nalias = \"a\"\ninput = \"b\"\n[pass.stages.scanlines]\n"
                                               "[[pass]]\nalias = \"b\"\ninput = \"a\"\n[pass.stages.vignette]\n"}},
                               "p");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().file == "p.toml");
        CHECK(p.error().line > 0);
        CHECK_THAT(p.error().message, Catch::Contains("cycle"));
    }
    SECTION("the same through the previous frame is feedback, not a cycle") {
        auto p = resolve_texts({{"p.toml", head +
                                               "[[pass]]\nalias = \"a\"\nscale_type = \"source\"\n[pass.textures]\nfeedback = \"b@previous\"\n"
                                               "[pass.stages.trails]\n"
                                               "[[pass]]\nalias = \"b\"\n[pass.stages.vignette]\n"}},
                               "p");
        INFO((p.ok() ? std::string() : p.error().str()));
        REQUIRE(p.ok());
        CHECK(p.value().has_feedback());
    }
    SECTION("a pass that does not exist") {
        auto p = resolve_texts({{"p.toml", head + "[[pass]]\nalias = \"a\"\ninput = \"nowhere\"\n[pass.stages.scanlines]\n"}}, "p");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().line == 3);
        CHECK_THAT(p.error().message, Catch::Contains("no pass 'nowhere'"));
    }
    SECTION("a LUT that does not exist") {
        auto p = resolve_texts({{"p.toml", head +
                                               "[[pass]]\nalias = \"a\"\n[pass.textures]\npalette = \"lut:missing\"\n"
                                               "[pass.stages.palette]\npaletteMode = \"nearest\"\n"}},
                               "p");
        REQUIRE_FALSE(p.ok());
        CHECK_THAT(p.error().message, Catch::Contains("[lut.missing]"));
    }
    SECTION("a texture a stage reads but the pass does not bind") {
        auto p = resolve_texts({{"p.toml", head + "[[pass]]\nalias = \"a\"\n[pass.stages.trails]\n"}}, "p");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().file == "p.toml");
        CHECK_THAT(p.error().message, Catch::Contains("reads texture 'feedback'"));
    }
    SECTION("a binding no stage reads") {
        auto p = resolve_texts({{"p.toml", head + "[[pass]]\nalias = \"a\"\n[pass.textures]\nnosuch = \"a@previous\"\n[pass.stages.vignette]\n"}},
                               "p");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().field == "pass.a.textures.nosuch");
        CHECK(p.error().line == 6);
    }
    SECTION("a mip chain's levels blend as the filter unless mip_filter says otherwise, which must be linear or nearest") {
        const std::string pass = "[[pass]]\nalias = \"a\"\nscale_type = \"source\"\n[pass.stages.vignette]\n"
                                 "[[pass]]\nalias = \"b\"\nfilter = \"linear\"\nmipmap = true\n";
        auto p = resolve_texts({{"p.toml", head + pass + "[pass.stages.scanlines]\n"}}, "p");
        INFO((p.ok() ? std::string() : p.error().str()));
        REQUIRE(p.ok());
        CHECK(p.value().passes[1].inputs.front().mipmap);
        CHECK(p.value().passes[1].inputs.front().mip_filter == Filter::Linear);
        auto nearest = resolve_texts({{"p.toml", head + pass + "mip_filter = \"nearest\"\n[pass.stages.scanlines]\n"}}, "p");
        REQUIRE(nearest.ok());
        CHECK(nearest.value().passes[1].inputs.front().mip_filter == Filter::Nearest);
        auto bad = resolve_texts({{"p.toml", head + pass + "mip_filter = \"cubic\"\n[pass.stages.scanlines]\n"}}, "p");
        REQUIRE_FALSE(bad.ok());
        CHECK(bad.error().line == 11);
        CHECK_THAT(bad.error().field, Catch::Contains("mip_filter"));
    }
}

TEST_CASE("scene geometry: screen rectangles per fit and pass sizes per scale type", "[scene]") {
    const Preset& win = *test::shipped_library().find_preset("super-win");
    // 4:3 in 1920x1080: pillarboxed, 1440 wide, centred.
    const PixelRect aspect = screen_rect(win, {1920, 1080}, {256, 224});
    CHECK(aspect.x == 240);
    CHECK(aspect.y == 0);
    CHECK(aspect.width == 1440);
    CHECK(aspect.height == 1080);
    // Stretch fills the display; integer keeps whole multiples of the source's 224 rows.
    const PixelRect stretch = screen_rect(win, {1920, 1080}, {256, 224}, DisplayFit::Stretch);
    CHECK(stretch.width == 1920);
    CHECK(stretch.height == 1080);
    const PixelRect integer = screen_rect(win, {1920, 1080}, {256, 224}, DisplayFit::Integer);
    CHECK(integer.height == 4 * 224);
    CHECK(integer.width == 1195);  // 896 * 4 / 3, rounded
    CHECK(integer.y == (1080 - 896) / 2);
    // The NES passes at source size, the screen at the screen's, the bloom at a sixteenth.
    const auto sizes = pass_sizes(win, {256, 224}, {1280, 960});
    REQUIRE(sizes.size() == win.passes.size());
    CHECK(sizes[0].width == 256);
    CHECK(sizes[0].height == 224);
    CHECK(sizes[2].width == 1280);
    CHECK(sizes[3].width == 80);
    CHECK(sizes[3].height == 60);
    CHECK(sizes.back().width == 1280);
    // 8:7 pixels fitted to the 4:3 screen's width: rows fall off the top and bottom.
    const auto scale = source_uv_scale(win);
    CHECK(scale[0] == 1.0);
    CHECK(scale[1] == Approx((256.0 * 8 / (224.0 * 7)) / (4.0 / 3.0)));
}

TEST_CASE("feedback reads the previous frame: a moving bar's trail decays by trailBlend * trailTint per frame",
          "[scene][feedback]") {
    // One pass holding Super Win the Game's trails, its feedback its own previous output. The bar
    // spans the width (so the trail's horizontal blur leaves it as it is) and moves down one bar
    // height a frame over black: where it was k frames ago, a pixel holds (blend * tint)^k.
    const double blend = 0.6;
    const std::array<double, 3> tint = {1.0, 0.7, 0.45};
    const Preset preset = trail_probe();
    constexpr int kSize = 32, kBar = 4, kLast = 5;
    const auto source = falling_bar(kSize, kBar);
    SECTION("trails on") {
        const SceneRenders r = render_both(preset, source, kSize, kSize, {kLast});
        for (const Image* image : {&r.vulkan.front(), &r.reference.front()}) {
            const bool vulkan = image == &r.vulkan.front();
            INFO((vulkan ? "Vulkan" : "reference"));
            const int mid = kSize / 2;
            // The bar itself, this frame.
            CHECK(image->at(mid, kLast * kBar + 1)[0] == Approx(1.0).margin(1e-3));
            for (int k = 1; k <= kLast; ++k) {
                const int row = (kLast - k) * kBar + 1;
                for (int c = 0; c < 3; ++c) {
                    INFO("k " << k << " channel " << c);
                    CHECK(image->at(mid, row)[c] == Approx(std::pow(blend * tint[c], k)).epsilon(0.01).margin(2e-3));
                }
                // Decay per frame: the ratio between a band and the one a frame older.
                if (k >= 2) {
                    const double newer = image->at(mid, (kLast - k + 1) * kBar + 1)[0], older = image->at(mid, row)[0];
                    CHECK(older / newer == Approx(blend * tint[0]).epsilon(0.01));
                }
            }
            // Below the bar nothing has been yet.
            CHECK(image->at(mid, kSize - 1)[0] == 0.0f);
        }
    }
    SECTION("trails off (blend 0): no trail at all") {
        const SceneRenders r = render_both(preset, source, kSize, kSize, {kLast}, {{"trailBlend", 0.0}});
        for (const Image* image : {&r.vulkan.front(), &r.reference.front()})
            for (int y = 0; y < kLast * kBar; ++y)
                for (int c = 0; c < 3; ++c) CHECK(image->at(kSize / 2, y)[c] == 0.0f);
    }
    SECTION("a still picture after the first frame: frame 0 has no previous frame (black)") {
        const SceneRenders r = render_both(preset, source, kSize, kSize, {0});
        for (const Image* image : {&r.vulkan.front(), &r.reference.front()}) CHECK(image->at(kSize / 2, kSize - 1)[0] == 0.0f);
    }
}

TEST_CASE("super-win's own trails: the moving sprite leaves a warm trail, and none with trails off", "[scene][feedback]") {
    const Preset& win = *test::shipped_library().find_preset("super-win");
    auto source = [](int frame) { return make_test_input("moving_sprite", kPixelArtWidth, kPixelArtHeight, frame); };
    const SceneRenders on = render_both(win, source, 320, 240, {6});
    const SceneRenders off = render_both(win, source, 320, 240, {6}, {{"trailBlend", 0.0}});
    // Where the sprite was, the image with trails is brighter and warmer (red above blue).
    double red_gain = 0, blue_gain = 0;
    for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x) {
            red_gain += on.vulkan[0].at(x, y)[0] - off.vulkan[0].at(x, y)[0];
            blue_gain += on.vulkan[0].at(x, y)[2] - off.vulkan[0].at(x, y)[2];
        }
    CHECK(red_gain > 1.0);
    CHECK(red_gain > blue_gain);
    // And trails off is the same image however the sprite moved before: frame 6 alone.
    auto moved = render_both(win, [&](int frame) { return source(6 + 0 * frame); }, 320, 240, {6}, {{"trailBlend", 0.0}});
    auto metrics = compare_images(moved.vulkan[0], off.vulkan[0]);
    REQUIRE(metrics.ok());
    CHECK(metrics.value().max_abs < 0.01);
}

TEST_CASE("the palette pass outputs palette colours only", "[scene][palette]") {
    const TemplateLibrary& lib = test::shipped_library();
    auto source = [](int) { return make_test_input("color_bars", 64, 48); };
    SECTION("levels: every channel on the grid of paletteSize / 4 levels") {
        for (const char* name : {"atari-16", "atari-64", "atari-128", "atari-256"}) {
            INFO(name);
            const Preset& p = *lib.find_preset(name);
            const int size = static_cast<int>(std::get<int64_t>(p.find_stage("palette")->values.at("paletteSize")));
            const double levels = size / 4.0;
            const SceneRenders r = render_both(p, source, 64, 48, {0});
            for (const Image* image : {&r.vulkan.front(), &r.reference.front()})
                for (size_t i = 0; i < image->rgba.size(); ++i) {
                    if (i % 4 == 3) continue;
                    const double steps = image->rgba[i] * levels;
                    CHECK(std::abs(steps - std::round(steps)) < 2e-3 * levels);
                }
        }
    }
    SECTION("nearest: every pixel one of the 128 colours of the Atari NTSC palette LUT") {
        const Preset& p = *lib.find_preset("atari-ntsc");
        auto lut = generate_lut("atari_ntsc", p.find_lut("ntsc")->params);
        REQUIRE(lut.ok());
        const SceneRenders r = render_both(p, source, 64, 48, {0});
        for (const Image* image : {&r.vulkan.front(), &r.reference.front()}) {
            size_t off_palette = 0;
            std::set<int> used;
            for (int y = 0; y < image->height; ++y)
                for (int x = 0; x < image->width; ++x) {
                    const float* px = image->at(x, y);
                    int found = -1;
                    for (int k = 0; k < 128 && found < 0; ++k) {
                        bool same = true;
                        for (int c = 0; c < 3; ++c) same = same && std::abs(px[c] - lut.value().rgba[k * 4 + c] / 255.0) < 1e-3;
                        if (same) found = k;
                    }
                    if (found < 0) ++off_palette;
                    else used.insert(found);
                }
            CHECK(off_palette == 0);
            CHECK(used.size() > 8);  // colour bars reach many palette entries, not one fallback
        }
    }
}

TEST_CASE("the palette LUT's cell lists hold every entry that can be nearest in the cell", "[scene][palette]") {
    const Preset& ntsc = *test::shipped_library().find_preset("atari-ntsc");
    auto lut = generate_lut("atari_ntsc", ntsc.find_lut("ntsc")->params);
    REQUIRE(lut.ok());
    const LutImage& image = lut.value();
    REQUIRE(image.width == 128);
    REQUIRE(image.height > 1);
    auto byte = [&](int x, int y, int c) { return static_cast<int>(image.rgba[(static_cast<size_t>(y) * 128 + static_cast<size_t>(x)) * 4 + static_cast<size_t>(c)]); };
    const int header_rows = (4096 + 127) / 128;
    // Each cell's list, read back as the shader reads it.
    auto list_of = [&](int cell) {
        const int first = byte(cell % 128, 1 + cell / 128, 0) + 256 * byte(cell % 128, 1 + cell / 128, 1);
        const int texels = byte(cell % 128, 1 + cell / 128, 2);
        std::vector<int> list;
        for (int t = first; t < first + texels; ++t)
            for (int c = 0; c < 4; ++c) list.push_back(byte(t % 128, 1 + header_rows + t / 128, c));
        return list;
    };
    size_t listed = 0;
    for (int cell = 0; cell < 4096; ++cell) {
        const std::vector<int> list = list_of(cell);
        REQUIRE(!list.empty());
        REQUIRE(list.size() % 4 == 0);
        bool ordered = true;  // ascending, then padding with the first
        for (size_t i = 1; i < list.size(); ++i) ordered = ordered && (list[i] > list[i - 1] || list[i] == list.front());
        if (!ordered) FAIL_CHECK("cell " << cell << "'s list is out of order");
        listed += list.size();
    }
    CHECK(listed < 4096 * 8);  // a few entries per cell, not the palette's 128
    // Colours all over the grid (and on its cell boundaries): the nearest entry, searched over the
    // whole palette in double precision, is always in the colour's cell's list.
    uint32_t state = 12345;
    int missing = 0;
    auto next = [&] { state = state * 1664525u + 1013904223u; return (state >> 8) / 16777216.0; };
    for (int n = 0; n < 20000; ++n) {
        double rgb[3];
        for (double& v : rgb) v = n % 4 == 0 ? -0.0625 + std::floor(next() * 17) * (1.125 / 16) : -0.0625 + 1.125 * next() * 0.999999;
        int best = 0;
        double best_distance = INFINITY;
        for (int i = 0; i < 128; ++i) {
            double d = 0;
            for (int c = 0; c < 3; ++c) d += std::pow(byte(i, 0, c) / 255.0 - rgb[c], 2);
            if (d < best_distance) best_distance = d, best = i;
        }
        int cell = 0;
        for (int c = 2; c >= 0; --c) cell = cell * 16 + std::clamp(static_cast<int>(std::floor((rgb[c] + 0.0625) * (16 / 1.125))), 0, 15);
        const std::vector<int> list = list_of(cell);
        if (std::find(list.begin(), list.end(), best) == list.end()) {
            FAIL_CHECK("colour " << rgb[0] << ", " << rgb[1] << ", " << rgb[2] << ": nearest entry " << best << " not in cell " << cell << "'s list");
            if (++missing > 5) break;
        }
    }
    CHECK(missing == 0);
}

TEST_CASE("the palette pass picks through its cell lists what a search of every entry picks", "[scene][palette]") {
    // Colours sweeping RGB past the grid's edges (they search the whole palette), and some that are
    // not numbers: Vulkan (the cell lists) against the reference (every entry, in double).
    const Preset& p = *test::shipped_library().find_preset("atari-ntsc");
    const int w = 96, h = 64;
    auto source = [&](int) -> Result<Image> {
        Image image = Image::make(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float r = -0.15f + 1.3f * (x % 32) / 31.0f, g = -0.15f + 1.3f * (y % 32) / 31.0f,
                            b = -0.15f + 1.3f * ((x / 32) + 3 * (y / 32)) / 5.0f;
                image.set_pixel(x, y, {r, g, b, 1.0f});
            }
        image.set_pixel(5, 5, {NAN, 0.5f, 0.5f, 1.0f});
        return image;
    };
    const SceneRenders r = render_both(p, source, w, h, {0});
    size_t different = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) different += std::abs(r.vulkan.front().at(x, y)[c] - r.reference.front().at(x, y)[c]) > 1e-3f;
    CHECK(different == 0);
}

TEST_CASE("the palette pass dithers with the article's 4x4 Bayer matrix", "[scene][palette]") {
    // palette.frag's matrix (column-major mat4, indexed by gl_FragCoord: x, then rows counted from
    // the bottom). For a flat input n + t levels above black, a pixel steps up to level n + 1 when
    // bayer / 16 >= 1 - t: sweeping t through the sixteen thresholds reveals each pixel's entry.
    const int bayer[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};  // [x][y from bottom]
    const Preset& p = *test::shipped_library().find_preset("atari-16");
    constexpr int kSize = 8;
    const double levels = 4.0;
    std::vector<std::array<std::array<int, kSize>, kSize>> first_up(2);  // per renderer: first k at which (x, y) is up
    for (auto& grid : first_up)
        for (auto& row : grid) row.fill(16);
    for (int k = 0; k < 16; ++k) {
        const double t = (k + 0.5) / 16.0, value = (1.0 + t) / levels;
        auto source = [value](int) -> Result<Image> {
            return Image::make(kSize, kSize, {static_cast<float>(value), static_cast<float>(value), static_cast<float>(value), 1.0f});
        };
        const SceneRenders r = render_both(p, source, kSize, kSize, {0});
        for (int which = 0; which < 2; ++which) {
            const Image& image = which == 0 ? r.vulkan.front() : r.reference.front();
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const double level = image.at(x, y)[0] * levels;
                    INFO("k " << k << " at " << x << "," << y << ": " << level);
                    REQUIRE((std::abs(level - 1.0) < 1e-3 || std::abs(level - 2.0) < 1e-3));
                    if (level > 1.5 && first_up[which][y][x] == 16) first_up[which][y][x] = k;
                }
        }
    }
    for (int which = 0; which < 2; ++which)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                INFO((which == 0 ? "Vulkan" : "reference") << " at " << x << "," << y);
                // Up from k on, where k + 0.5 >= 16 - bayer: k = 16 - bayer (never, for entry 0).
                CHECK(first_up[which][y][x] == 16 - bayer[x % 4][(kSize - 1 - y) % 4]);
            }
}

TEST_CASE("LUT generators: a neutral grade is the identity, the Atari palette's hue 0 is greys", "[scene][lut]") {
    auto grade = generate_lut("yiq_grade", {{"hue", 0.0}, {"saturation", 1.0}, {"contrast", 1.0}, {"brightness", 0.0}, {"gamma", 1.0}});
    REQUIRE(grade.ok());
    CHECK(grade.value().width == 1024);
    CHECK(grade.value().height == 32);
    int worst = 0;
    for (int g = 0; g < 32; ++g)
        for (int b = 0; b < 32; ++b)
            for (int r = 0; r < 32; ++r) {
                const uint8_t* px = &grade.value().rgba[(static_cast<size_t>(g) * 1024 + static_cast<size_t>(b * 32 + r)) * 4];
                const int want[3] = {static_cast<int>(std::lround(r * 255 / 31.0)), static_cast<int>(std::lround(g * 255 / 31.0)),
                                     static_cast<int>(std::lround(b * 255 / 31.0))};
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(px[c] - want[c]));
            }
    CHECK(worst <= 1);  // the FCC YIQ matrices are inverses to 3 decimals

    const Preset& ntsc = *test::shipped_library().find_preset("atari-ntsc");
    auto palette = generate_lut("atari_ntsc", ntsc.find_lut("ntsc")->params);
    REQUIRE(palette.ok());
    REQUIRE(palette.value().width == 128);
    int previous = -1;
    for (int lum = 0; lum < 8; ++lum) {
        const uint8_t* px = &palette.value().rgba[static_cast<size_t>(lum) * 4];
        CHECK(px[0] == px[1]);
        CHECK(px[1] == px[2]);
        CHECK(static_cast<int>(px[0]) > previous);
        previous = px[0];
    }
    std::set<uint32_t> distinct;
    for (int k = 0; k < 128; ++k) {
        const uint8_t* px = &palette.value().rgba[static_cast<size_t>(k) * 4];
        distinct.insert(static_cast<uint32_t>(px[0]) << 16 | static_cast<uint32_t>(px[1]) << 8 | px[2]);
    }
    CHECK(distinct.size() > 100);
    // Unknown generators and params are errors that name them.
    auto unknown = generate_lut("nope", {});
    REQUIRE_FALSE(unknown.ok());
    CHECK_THAT(unknown.error().message, Catch::Contains("nope"));
}

TEST_CASE("the exported Godot 3 scene keeps the previous frame: the trail decays there too", "[scene][feedback][godot3]") {
    const Preset preset = trail_probe();
    constexpr int kSize = 32, kBar = 4, kLast = 3;
    const auto source = falling_bar(kSize, kBar);
    auto compiled = compile_scene(test::shipped_library(), preset, {}, Cache());
    REQUIRE(compiled.ok());
    auto outputs = emit_scene(compiled.value(), TargetId::Godot3, Cache());
    REQUIRE(outputs.ok());
    TargetRenderer renderer;
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &compiled.value();
    r.target = TargetId::Godot3;
    r.outputs = &outputs.value();
    r.source = source;
    r.width = kSize;
    r.height = kSize;
    r.frames = {kLast};
    auto images = renderer.render_scene(r);
    INFO((images.ok() ? std::string() : images.error().str()));
    REQUIRE(images.ok());
    const Image& image = images.value().front();
    // Godot 3 keeps the 8-bit pass in an 8-bit viewport: values within 1/255 of (0.6 * tint)^k.
    for (int k = 1; k <= kLast; ++k)
        for (int c = 0; c < 3; ++c) {
            INFO("k " << k << " channel " << c);
            const double tint[3] = {1.0, 0.7, 0.45};
            CHECK(image.at(kSize / 2, (kLast - k) * kBar + 1)[c] == Approx(std::pow(0.6 * tint[c], k)).margin(2.5 / 255));
        }
    CHECK(image.at(kSize / 2, kSize - 1)[0] == 0.0f);
}

TEST_CASE("a preset's declared tiers change its passes' scales and stages and come before the point tier", "[scene][tiers]") {
    const std::string scene = "name = \"p\"\ndoc = \"d\"\n"
                              "[[pass]]\nalias = \"screen\"\nscale_type = \"viewport\"\n[pass.stages.mask]\nmaskMode = \"grille\"\n"
                              "[[pass]]\nalias = \"blur\"\nscale_type = \"viewport\"\n[pass.stages.poisson_blur]\nblurRadius = 8.0\n";
    const std::string tier = "[tiers.cheap]\ndoc = \"a smaller blur\"\n[tiers.cheap.passes.blur]\nscale = 0.5\n"
                             "[tiers.cheap.passes.blur.stages.poisson_blur]\nblurRadius = 4.0\n";
    const Preset preset = resolve_or_fail(scene + tier, "p");
    REQUIRE(preset.tiers.size() == 1);
    const DeclaredTier& cheap = preset.tiers.front();
    CHECK(cheap.name == "cheap");
    CHECK(cheap.doc == "a smaller blur");
    CHECK(cheap.where.line == 13);
    REQUIRE(cheap.preset);
    const Pass* blur = cheap.preset->find_pass("blur");
    REQUIRE(blur);
    CHECK(blur->scale_x.factor == 0.5);
    CHECK(blur->scale_y.factor == 0.5);
    CHECK(blur->scale_x.type == PassScale::Type::Viewport);
    CHECK(std::get<double>(blur->find_stage("poisson_blur")->values.at("blurRadius")) == 4.0);
    CHECK(cheap.preset->tiers.empty());
    CHECK(cheap.changes == std::vector<std::string>{"pass blur: scale 1.0 -> 0.5", "pass blur: poisson_blur.blurRadius 8.0 -> 4.0"});
    // The preset itself is as written.
    CHECK(preset.find_pass("blur")->scale_x.factor == 1.0);
    CHECK(std::get<double>(preset.find_pass("blur")->find_stage("poisson_blur")->values.at("blurRadius")) == 8.0);

    // The declared tier first, as written and with every stage filtered, then point and filtered.
    const std::vector<PresetTier> tiers = preset_tiers(preset);
    std::vector<std::string> names;
    for (const PresetTier& t : tiers) names.push_back(t.name);
    CHECK(names == std::vector<std::string>{"cheap", "cheap+filtered", "point", "filtered"});
    CHECK(tiers[0].declared == "cheap");
    CHECK(tiers[1].preset.find_pass("screen")->find_stage("mask")->form->name == "grille_filtered");
    CHECK(tiers[1].preset.find_pass("blur")->scale_x.factor == 0.5);
    CHECK(tiers[2].preset.find_pass("blur")->scale_x.factor == 1.0);
}

TEST_CASE("a derived preset inherits its base's tiers and may rescale a base's pass", "[scene][tiers]") {
    const std::string base = "name = \"b\"\ndoc = \"d\"\n"
                             "[[pass]]\nalias = \"a\"\nscale_type = \"source\"\n[pass.stages.vignette]\n"
                             "[[pass]]\nalias = \"z\"\n[pass.stages.scanlines]\n"
                             "[tiers.half]\ndoc = \"half\"\n[tiers.half.passes.a]\nscale = 0.5\n";
    const std::string derived = "name = \"c\"\ndoc = \"d\"\nbase = \"b\"\n[passes.a]\nscale = 2.0\n";
    auto p = resolve_texts({{"b.toml", base}, {"c.toml", derived}}, "c");
    INFO((p.ok() ? std::string() : p.error().str()));
    REQUIRE(p.ok());
    CHECK(p.value().find_pass("a")->scale_x.factor == 2.0);
    REQUIRE(p.value().tiers.size() == 1);
    CHECK(p.value().tiers.front().preset->find_pass("a")->scale_x.factor == 0.5);
    CHECK(p.value().tiers.front().where.file == "b.toml");
}

namespace {

// A preset p.toml of `head` and each case's text fails to resolve at the case's field and line.
struct ErrorCase {
    std::string text, field, says;
    int line;
};

void check_errors(const std::string& head, const std::vector<ErrorCase>& cases) {
    for (const ErrorCase& c : cases) {
        INFO(c.text);
        auto p = resolve_texts({{"p.toml", head + c.text}}, "p");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().file == "p.toml");
        CHECK(p.error().field == c.field);
        CHECK(p.error().line == c.line);
        CHECK_THAT(p.error().message, Catch::Contains(c.says));
    }
}

}  // namespace

TEST_CASE("a bad declared tier is a file:line error naming its field", "[scene][tiers][errors]") {
    const std::string head = "name = \"p\"\ndoc = \"d\"\n[[pass]]\nalias = \"a\"\nscale_type = \"source\"\n[pass.stages.vignette]\n"
                             "[[pass]]\nalias = \"px\"\nscale_type = \"absolute\"\nscale = 64\n[pass.stages.scanlines]\n";
    const std::vector<ErrorCase> cases = {
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.nope]\nscale = 0.5\n", "tiers.t.passes.nope", "no pass 'nope'", 14},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.px]\nscale = 0.5\n", "tiers.t.passes.px.scale", "absolute size", 15},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a]\nscale = 0.0\n", "tiers.t.passes.a.scale", "above 0", 15},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a]\nscale = 17.0\n", "tiers.t.passes.a.scale", "at most 16", 15},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a]\nscale = \"half\"\n", "tiers.t.passes.a.scale", "must be a number", 15},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a]\nsize = 2\n", "tiers.t.passes.a.size", "", 15},
        {"[tiers.point]\ndoc = \"x\"\n[tiers.point.passes.a]\nscale = 0.5\n", "tiers.point", "not 'point'", 12},
        {"[tiers.t]\n[tiers.t.passes.a]\nscale = 0.5\n", "tiers.t.doc", "", 12},
        {"[tiers.t]\ndoc = \"x\"\n", "tiers.t.passes", "at least one pass", 12},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a.stages.vignette]\nnoSuchParam = 1.0\n", "tiers.t.passes.a.stages.vignette.noSuchParam",
         "unknown param", 15},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a.stages.trails]\n", "tiers.t.passes.a.stages", "reads texture 'feedback'", 14},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a]\nsupersample = 0\n", "tiers.t.passes.a.supersample", "must be 1..4", 15},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a]\nsupersample = 5\n", "tiers.t.passes.a.supersample", "must be 1..4", 15},
        {"[tiers.t]\ndoc = \"x\"\n[tiers.t.passes.a]\nsupersample = 1.5\n", "tiers.t.passes.a.supersample", "", 15},
    };
    check_errors(head, cases);
}

TEST_CASE("a supersampled pass needs stages to average and 1..4 samples a side", "[scene][tiers][errors]") {
    const std::string head = "name = \"p\"\ndoc = \"d\"\n[[pass]]\nalias = \"a\"\n[pass.stages.vignette]\n[[pass]]\nalias = \"b\"\n";
    const std::vector<ErrorCase> cases = {
        {"supersample = 2\n", "pass.b.supersample", "no stages", 6},
        {"supersample = 9\n[pass.stages.vignette]\n", "pass.b.supersample", "must be 1..4", 8},
        {"supersample = true\n[pass.stages.vignette]\n", "pass.b.supersample", "", 8},
    };
    check_errors(head, cases);
    // Set in a [[pass]], and inherited and changed by a derived preset's [passes.<alias>].
    const std::string good = head + "supersample = 2\n[pass.stages.vignette]\n";
    auto base = resolve_texts({{"p.toml", good}}, "p");
    REQUIRE(base.ok());
    CHECK(base.value().passes[1].supersample == 2);
    CHECK(base.value().passes[0].supersample == 1);
    auto derived = resolve_texts({{"p.toml", good}, {"q.toml", "name = \"q\"\ndoc = \"d\"\nbase = \"p\"\n[passes.a]\nsupersample = 3\n"}}, "q");
    REQUIRE(derived.ok());
    CHECK(derived.value().passes[0].supersample == 3);
    CHECK(derived.value().passes[1].supersample == 2);
}

TEST_CASE("a derived preset that drops a pass drops the base's tiers of it, and keeps its own refusal of unknown passes", "[scene][tiers]") {
    // super-win without its bloom: bloom_down and bloom_up are read by nothing and dropped, and the
    // quarter-bloom tier, which only changes those two passes, goes with them.
    test::ScratchTemplates t;
    t.write("presets/sw-nobloom.toml", "format = 2\nname = \"sw-nobloom\"\nbase = \"super-win\"\ndoc = \"no bloom\"\n"
                                       "[passes.composite.stages.bloom_add]\nenabled = false\n");
    auto lib = t.load();
    INFO((lib.ok() ? std::string() : lib.error().str()));
    REQUIRE(lib.ok());
    const Preset* derived = lib.value()->find_preset("sw-nobloom");
    REQUIRE(derived);
    CHECK_FALSE(derived->find_pass("bloom_down"));
    CHECK_FALSE(derived->find_pass("bloom_up"));
    for (const DeclaredTier& tier : derived->tiers) CHECK(tier.name != "quarter-bloom");
    const Preset* base = lib.value()->find_preset("super-win");
    REQUIRE(base);
    CHECK(std::any_of(base->tiers.begin(), base->tiers.end(), [](const DeclaredTier& d) { return d.name == "quarter-bloom"; }));
    // A tier the derived preset declares itself still names only passes it has.
    t.write("presets/sw-nobloom.toml", "format = 2\nname = \"sw-nobloom\"\nbase = \"super-win\"\ndoc = \"no bloom\"\n"
                                       "[passes.composite.stages.bloom_add]\nenabled = false\n"
                                       "[tiers.mine]\ndoc = \"d\"\n[tiers.mine.passes.bloom_up]\nscale = 0.5\n");
    auto refused = t.load();
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().str(), Catch::Contains("sw-nobloom.toml:9") && Catch::Contains("there is no pass 'bloom_up'"));
}

// The formats a pass may store beyond 8-bit and half float (RetroArch's R32G32B32A32_SFLOAT,
// A2B10G10R10_UNORM_PACK32, R16_SFLOAT, R16G16_SFLOAT): a plain copy stored in each, shown by a
// second copy, on Vulkan and in the fp64 reference. The picture's values lie off every grid
// (and one channel past 1), so each format's rounding, clamping and missing channels show.
TEST_CASE("rgba32f, rgb10a2, r16f and rg16f passes store what their formats hold, on Vulkan and in the reference", "[scene][format]") {
    constexpr int kSize = 8;
    Image picture = Image::make(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            picture.set_pixel(x, y, {0.1f + 0.0371f * static_cast<float>(x), 0.2f + 0.0913f * static_cast<float>(y), 1.3f, 0.41f});
    const auto source = [&](int) -> Result<Image> { return picture; };
    for (const char* format : {"rgba32f", "rgb10a2", "r16f", "rg16f"}) {
        INFO(format);
        const Preset preset = resolve_or_fail(fmt::format("name = \"format-probe\"\ndoc = \"d\"\n"
                                                          "[[pass]]\nalias = \"stored\"\nscale_type = \"source\"\nfilter = \"nearest\"\nformat = \"{}\"\n"
                                                          "[[pass]]\nalias = \"shown\"\nscale_type = \"viewport\"\nfilter = \"nearest\"\n",
                                                          format),
                                              "format-probe");
        REQUIRE(std::string(pixel_format_name(preset.passes[0].format)) == format);
        // A float display: the stored pass's grid is what the picture shows.
        const SceneRenders r = render_both(preset, source, kSize, kSize, {0}, {}, OutputFormat::Rgba32Float);
        for (const Image* image : {&r.vulkan.front(), &r.reference.front()}) {
            INFO((image == &r.vulkan.front() ? "Vulkan" : "reference"));
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x) {
                    const float *in = picture.at(x, y), *out = image->at(x, y);
                    for (int c = 0; c < 4; ++c) {
                        INFO("pixel " << x << "," << y << " channel " << c);
                        const std::string f = format;
                        if (f == "rgba32f") CHECK(out[c] == Approx(in[c]).margin(1e-6));
                        else if (f == "rgb10a2") {
                            // Clamped, then on the format's grid: the nearest step in the reference, a
                            // step either side on a device (its original is half floats: 858.4 / 1023
                            // reads as 858.67 / 1023 and stores 859).
                            const double steps = c == 3 ? 3.0 : 1023.0, at = out[c] * steps;
                            CHECK(std::abs(at - std::round(at)) < 1e-3);
                            CHECK(std::abs(at - std::min(in[c], 1.0f) * steps) <= (image == &r.vulkan.front() ? 1.0 : 0.5));
                        } else {
                            const int kept = f == "r16f" ? 1 : 2;  // half floats: 2^-11 relative
                            if (c < kept) CHECK(out[c] == Approx(in[c]).epsilon(1.0 / 1024));
                            else CHECK(out[c] == (c == 3 ? 1.0f : 0.0f));
                        }
                    }
                }
        }
        // The two agree closely, not only each with the formula.
        auto same = compare_images(r.vulkan.front(), r.reference.front());
        REQUIRE(same.ok());
        CHECK(same.value().max_abs < 1e-3);  // a half's rounding: nearest or towards 0
    }
}
