// Physical checks on rendered output (Vulkan, lavapipe): the properties the documents promise,
// measured from pixels rather than read from the code.
#include <cmath>
#include <complex>

#include <catch2/catch.hpp>

#include "crtforge/validate/target_render.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

Preset resolve_inline(const std::string& text) {
    const TemplateLibrary& lib = test::shipped_library();
    auto file = parse_preset_file(text, "inline.toml", &lib);
    REQUIRE(file.ok());
    auto preset = lib.resolve({file.value()}, file.value().name);
    if (!preset.ok()) FAIL(preset.error().str());
    return preset.value();
}

Image render(const Preset& preset, const Image& input, int w, int h, SamplerFilter filter = SamplerFilter::Linear) {
    static TargetRenderer renderer(EngineOptions{"", true});  // validation layers on: any message fails
    auto compiled = compile_variant(test::shipped_library(), preset, {}, Cache());
    REQUIRE(compiled.ok());
    TargetRenderRequest r;
    r.compiled = &compiled.value();
    r.input = input;
    r.filter = filter;
    r.width = w;
    r.height = h;
    auto image = renderer.render(r);
    if (!image.ok()) FAIL(image.error().str());
    return image.value();
}

double luma(const Image& img, int x, int y) {
    const float* p = img.at(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

// The dominant period (in pixels) of a signal, from the peak of its DFT magnitude (mean removed),
// refined by parabolic interpolation between neighbouring bins.
double dominant_period(const std::vector<double>& signal) {
    const size_t n = signal.size();
    double mean = 0;
    for (double v : signal) mean += v / n;
    std::vector<double> mag(n / 2 + 1);
    for (size_t k = 1; k <= n / 2; ++k) {
        std::complex<double> sum = 0;
        for (size_t i = 0; i < n; ++i) sum += (signal[i] - mean) * std::polar(1.0, -2.0 * M_PI * k * i / n);
        mag[k] = std::abs(sum);
    }
    size_t best = 1;
    for (size_t k = 1; k <= n / 2; ++k)
        if (mag[k] > mag[best]) best = k;
    double shift = 0;
    if (best > 1 && best < n / 2) {
        const double a = mag[best - 1], b = mag[best], c = mag[best + 1];
        shift = 0.5 * (a - c) / (a - 2 * b + c);
    }
    return n / (best + shift);
}

Image flat(int w, int h, float v) { return Image::make(w, h, {v, v, v, 1.0f}); }

}  // namespace

TEST_CASE("WebGPU scanlines repeat every 4 device pixels at any output height", "[physical]") {
    const Preset* web = test::shipped_library().find_preset("webgpu-post");
    for (int height : {240, 333, 480, 601}) {
        INFO("height " << height);
        Image out = render(*web, flat(64, 64, 0.5f), 64, height);
        std::vector<double> rows;
        for (int y = 0; y < height; ++y) rows.push_back(luma(out, 32, y));
        CHECK(dominant_period(rows) == Approx(4.0).margin(0.02));
    }
}

TEST_CASE("the other scanline forms keep their documented spacing", "[physical]") {
    SECTION("CRT effect: scanlineSpacing 3 px between lines, i.e. a 6 px sine period") {
        Preset p = resolve_inline("name = \"s\"\ndoc = \"d\"\n[stages.scanlines]\nscanlineForm = \"crt_effect\"\nscanlineSpacing = 3.0\nscanlineBrightBoost = 0.0\n");
        Image out = render(p, flat(32, 32, 0.5f), 32, 240);
        std::vector<double> rows;
        for (int y = 0; y < 240; ++y) rows.push_back(luma(out, 16, y));
        CHECK(dominant_period(rows) == Approx(6.0).margin(0.05));
    }
    SECTION("Quiet Frame: every other row dimmed (2 px period)") {
        Preset p = resolve_inline("name = \"s\"\ndoc = \"d\"\n[stages.scanlines]\nscanlineForm = \"quiet_frame\"\nscanlineIntensity = 0.5\n");
        Image out = render(p, flat(16, 16, 0.8f), 16, 20);
        for (int y = 0; y + 1 < 20; ++y) CHECK(std::abs(luma(out, 8, y) - luma(out, 8, y + 1)) > 0.3);
    }
}

TEST_CASE("curvature keeps the centre pixel and puts the bezel in the corners", "[physical]") {
    // A 2x2-texel-per-pixel checker would blur; use a smooth ramp so a moved centre is visible.
    Image ramp = Image::make(101, 101);
    for (int y = 0; y < 101; ++y)
        for (int x = 0; x < 101; ++x) ramp.set_pixel(x, y, {x / 100.0f, y / 100.0f, 0.25f, 1.0f});
    for (const char* form : {"atari", "crt_effect", "quiet_frame"}) {
        INFO(form);
        Preset p = resolve_inline(std::string("name = \"c\"\ndoc = \"d\"\n[stages.curvature]\ncurvatureForm = \"") + form +
                                  "\"\ncurvature = 0.3\nbezelColor = \"#000000\"\n");
        Image out = render(p, ramp, 101, 101, SamplerFilter::Nearest);
        for (int c = 0; c < 3; ++c) CHECK(out.at(50, 50)[c] == Approx(ramp.at(50, 50)[c]).margin(1e-3));
        for (auto [x, y] : {std::pair{0, 0}, {100, 0}, {0, 100}, {100, 100}})
            for (int c = 0; c < 3; ++c) CHECK(out.at(x, y)[c] == 0.0f);
    }
}

TEST_CASE("every vignette form darkens monotonically from the centre", "[physical]") {
    for (const char* form : {"atari", "crt_effect", "quiet_frame"}) {
        INFO(form);
        Preset p = resolve_inline(std::string("name = \"v\"\ndoc = \"d\"\n[stages.vignette]\nvignetteForm = \"") + form + "\"\n");
        Image out = render(p, flat(120, 90, 1.0f), 120, 90);
        // Along the row and the diagonal from the centre outwards, brightness never increases.
        for (int x = 60; x + 1 < 120; ++x) CHECK(luma(out, x + 1, 45) <= luma(out, x, 45) + 1e-6);
        for (int i = 0; i + 1 < 45; ++i) CHECK(luma(out, 60 + i + 1, 45 + i + 1) <= luma(out, 60 + i, 45 + i) + 1e-6);
        CHECK(luma(out, 119, 89) < luma(out, 60, 45));
    }
}

TEST_CASE("the shadow mask repeats every maskSize pixels and grille stripes are maskSize wide", "[physical]") {
    for (double size : {6.0, 8.0, 12.0}) {
        INFO("maskSize " << size);
        Preset shadow = resolve_inline("name = \"m\"\ndoc = \"d\"\n[stages.mask]\nmaskMode = \"shadow\"\nmaskQuantize = false\nmaskSize = " +
                                       std::to_string(size) + "\n");
        Image out = render(shadow, flat(192, 48, 0.5f), 192, 48);
        std::vector<double> red;
        for (int x = 0; x < 192; ++x) red.push_back(out.at(x, 5)[0]);
        CHECK(dominant_period(red) == Approx(size).margin(0.05));

        Preset grille = resolve_inline("name = \"m\"\ndoc = \"d\"\n[stages.mask]\nmaskMode = \"grille\"\nmaskSize = " + std::to_string(size) + "\n");
        Image g = render(grille, flat(144, 16, 0.5f), 144, 16);
        std::vector<double> gred;
        for (int x = 0; x < 144; ++x) gred.push_back(g.at(x, 5)[0]);
        // One R, G, B triad of maskSize-wide stripes per 3 * maskSize pixels (the document's formula).
        CHECK(dominant_period(gred) == Approx(3 * size).margin(0.15));
    }
}

TEST_CASE("a disabled stage changes nothing", "[physical]") {
    const TemplateLibrary& lib = test::shipped_library();
    Image input = Image::make(80, 60);
    for (int y = 0; y < 60; ++y)
        // Multiples of 1/128: exactly representable in the RGBA16F output, so "exactly" means exactly.
        for (int x = 0; x < 80; ++x) input.set_pixel(x, y, {x / 128.0f, y / 64.0f, ((x ^ y) & 1) * 1.0f, 1.0f});
    SECTION("passthrough reproduces the input exactly") {
        Image out = render(*lib.find_preset("passthrough"), input, 80, 60, SamplerFilter::Nearest);
        CHECK(out.rgba == input.rgba);
    }
    SECTION("a preset with an inherited stage switched off renders like one that never had it") {
        Preset with_glow_off = resolve_inline("name = \"a\"\ndoc = \"d\"\n[stages.scanlines]\n[stages.glow]\nenabled = false\n");
        Preset never = resolve_inline("name = \"b\"\ndoc = \"d\"\n[stages.scanlines]\n");
        CHECK(render(with_glow_off, input, 80, 60).rgba == render(never, input, 80, 60).rgba);
    }
}
