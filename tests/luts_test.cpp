// The generated LUTs against published values: the Atari 2600 NTSC palette crtforge generates,
// entry by entry, against the table emulators publish (an independent check of a fact the reference
// and every host share, since they all read the same generated LUT).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <catch2/catch.hpp>

#include "crtforge/luts.hpp"

using namespace crtforge;

namespace {

// Stella's standard NTSC palette (stella-emu/stella, src/common/PaletteHandler.cxx,
// ourNTSCPalette, its even entries): 16 hues x 8 luminances, 0xRRGGBB. Test data, not used by the
// product: the generator keeps only each hue's two end colours; the six between come from its curve.
constexpr uint32_t kStellaNtsc[128] = {
    0x000000, 0x4a4a4a, 0x6f6f6f, 0x8e8e8e, 0xaaaaaa, 0xc0c0c0, 0xd6d6d6, 0xececec,
    0x484800, 0x69690f, 0x86861d, 0xa2a22a, 0xbbbb35, 0xd2d240, 0xe8e84a, 0xfcfc54,
    0x7c2c00, 0x904811, 0xa26221, 0xb47a30, 0xc3903d, 0xd2a44a, 0xdfb755, 0xecc860,
    0x901c00, 0xa33915, 0xb55328, 0xc66c3a, 0xd5824a, 0xe39759, 0xf0aa67, 0xfcbc74,
    0x940000, 0xa71a1a, 0xb83232, 0xc84848, 0xd65c5c, 0xe46f6f, 0xf08080, 0xfc9090,
    0x840064, 0x97197a, 0xa8308f, 0xb846a2, 0xc659b3, 0xd46cc3, 0xe07cd2, 0xec8ce0,
    0x500084, 0x68199a, 0x7d30ad, 0x9246c0, 0xa459d0, 0xb56ce0, 0xc57cee, 0xd48cfc,
    0x140090, 0x331aa3, 0x4e32b5, 0x6848c6, 0x7f5cd5, 0x956fe3, 0xa980f0, 0xbc90fc,
    0x000094, 0x181aa7, 0x2d32b8, 0x4248c8, 0x545cd6, 0x656fe4, 0x7580f0, 0x8490fc,
    0x001c88, 0x183b9d, 0x2d57b0, 0x4272c2, 0x548ad2, 0x65a0e1, 0x75b5ef, 0x84c8fc,
    0x003064, 0x185080, 0x2d6d98, 0x4288b0, 0x54a0c5, 0x65b7d9, 0x75cceb, 0x84e0fc,
    0x004030, 0x18624e, 0x2d8169, 0x429e82, 0x54b899, 0x65d1ae, 0x75e7c2, 0x84fcd4,
    0x004400, 0x1a661a, 0x328432, 0x48a048, 0x5cba5c, 0x6fd26f, 0x80e880, 0x90fc90,
    0x143c00, 0x355f18, 0x527e2d, 0x6e9c42, 0x87b754, 0x9ed065, 0xb4e775, 0xc8fc84,
    0x303800, 0x505916, 0x6d762b, 0x88923e, 0xa0ab4f, 0xb7c25f, 0xccd86e, 0xe0ec7c,
    0x482c00, 0x694d14, 0x866a26, 0xa28638, 0xbb9f47, 0xd2b656, 0xe8cc63, 0xfce070,
};

// sRGB bytes -> CIE L*a*b* (D65).
std::array<double, 3> lab(int r8, int g8, int b8) {
    auto linear = [](int v) {
        const double c = v / 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    const double r = linear(r8), g = linear(g8), b = linear(b8);
    const double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047, y = 0.2126 * r + 0.7152 * g + 0.0722 * b,
                 z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    auto f = [](double t) { return t > 216.0 / 24389.0 ? std::cbrt(t) : t * 24389.0 / 27.0 / 116.0 + 16.0 / 116.0; };
    return {116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
}

double delta_e76(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

TEST_CASE("atari_ntsc is within dE76 5 of Stella's published NTSC palette at every entry", "[luts][palette]") {
    auto lut = generate_lut("atari_ntsc", {});
    REQUIRE(lut.ok());
    double worst = 0, sum = 0, worst_between = 0;
    for (int i = 0; i < 128; ++i) {
        const uint8_t* px = &lut.value().rgba[static_cast<size_t>(i) * 4];
        const uint32_t t = kStellaNtsc[i];
        const double d = delta_e76(lab(px[0], px[1], px[2]), lab((t >> 16) & 0xff, (t >> 8) & 0xff, t & 0xff));
        INFO("entry " << i << " (hue " << i / 8 << ", luminance " << i % 8 << "): dE76 " << d);
        CHECK(d <= 5.0);
        worst = std::max(worst, d);
        sum += d;
        if (i % 8 != 0 && i % 8 != 7) worst_between = std::max(worst_between, d);
    }
    WARN("atari_ntsc vs Stella's NTSC table: worst dE76 " << worst << ", worst between the ends " << worst_between << ", mean "
                                                        << sum / 128);
    // What the generator's comment states (the six luminances between each hue's ends come from
    // its curve, the grey ramp from its power law): all within 1.
    CHECK(worst < 1.0);
    CHECK(worst_between < 1.0);
    CHECK(sum / 128 < 0.3);
    // Luminance 0 of a colour hue is dark, not black; of hue 0 it is black.
    CHECK(lut.value().rgba[0] == 0);
    CHECK(lut.value().rgba[8 * 4 * 4] > 0x80);  // hue 4 (red), luminance 0: 0x94 in the table
}

TEST_CASE("atari_ntsc's saturation scales chroma about the luma: 0 is grey, 1 the table", "[luts][palette]") {
    auto grey = generate_lut("atari_ntsc", {{"saturation", 0.0}});
    REQUIRE(grey.ok());
    for (int i = 0; i < 128; ++i) {
        const uint8_t* px = &grey.value().rgba[static_cast<size_t>(i) * 4];
        CHECK(std::abs(px[0] - px[1]) <= 1);
        CHECK(std::abs(px[1] - px[2]) <= 1);
    }
    auto bad = generate_lut("atari_ntsc", {{"saturation", 3.0}});
    CHECK_FALSE(bad.ok());
}
