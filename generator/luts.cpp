// The LUT generators and the PNG writer for their files (see crtforge/luts.hpp).
#include "crtforge/luts.hpp"
#include "generator/palette_cells.hpp"

#include <algorithm>
#include <cmath>

#include <zlib.h>

namespace crtforge {

namespace {

constexpr double kPi = 3.14159265358979323846;

uint8_t to_byte(double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

double param(const std::map<std::string, double>& p, const char* name) { return p.at(name); }

// FCC NTSC YIQ <-> R'G'B' (gamma-encoded signal values, as the NTSC signal carries them).
struct Yiq {
    double y, i, q;
};
Yiq rgb_to_yiq(double r, double g, double b) {
    return {0.299 * r + 0.587 * g + 0.114 * b, 0.596 * r - 0.274 * g - 0.322 * b, 0.211 * r - 0.523 * g + 0.312 * b};
}
void yiq_to_rgb(const Yiq& c, double rgb[3]) {
    rgb[0] = c.y + 0.956 * c.i + 0.621 * c.q;
    rgb[1] = c.y - 0.272 * c.i - 0.647 * c.q;
    rgb[2] = c.y - 1.106 * c.i + 1.703 * c.q;
}

LutImage yiq_grade(const std::map<std::string, double>& p) {
    const double hue = param(p, "hue") * kPi / 180.0, saturation = param(p, "saturation"),
                 contrast = param(p, "contrast"), brightness = param(p, "brightness"), gamma = param(p, "gamma");
    constexpr int n = 32;
    LutImage out;
    out.width = n * n;
    out.height = n;
    out.rgba.resize(static_cast<size_t>(out.width) * out.height * 4);
    for (int g = 0; g < n; ++g)
        for (int b = 0; b < n; ++b)
            for (int r = 0; r < n; ++r) {
                Yiq c = rgb_to_yiq(r / 31.0, g / 31.0, b / 31.0);
                // Tint: rotate the chroma; colour: scale it; contrast about mid-grey, then brightness.
                const double i = c.i * std::cos(hue) - c.q * std::sin(hue), q = c.i * std::sin(hue) + c.q * std::cos(hue);
                c = {(c.y - 0.5) * contrast + 0.5 + brightness, i * saturation, q * saturation};
                double rgb[3];
                yiq_to_rgb(c, rgb);
                uint8_t* px = &out.rgba[(static_cast<size_t>(g) * out.width + static_cast<size_t>(b * n + r)) * 4];
                for (int k = 0; k < 3; ++k) px[k] = to_byte(std::pow(std::clamp(rgb[k], 0.0, 1.0), gamma));
                px[3] = 255;
            }
    return out;
}

// The Atari 2600's NTSC palette as emulators publish it (Stella's standard NTSC table,
// src/common/PaletteHandler.cxx, ourNTSCPalette) follows one rule, which this generator states:
// hue 0 is grey, g(l) = peak * (l / 7)^gamma; each colour hue runs from its darkest colour
// (luminance 0: the hue's chroma clipped against black) to its brightest (luminance 7: clipped
// against peak white) along one curve all hues share, f(l) = ln(1 + l / k) / ln(1 + 7 / k). The
// 15 hues' two end colours are the table's: no YIQ model with one phase step and amplitude
// reproduces them (the best such fit is dE76 13 off at its worst entry, 8 on average); the six
// luminances between them come from the curve, within dE76 0.71 of the table (measured for every
// entry by tests/luts_test.cpp).
constexpr uint8_t kAtariHueEnds[15][2][3] = {
    {{0x48, 0x48, 0x00}, {0xfc, 0xfc, 0x54}}, {{0x7c, 0x2c, 0x00}, {0xec, 0xc8, 0x60}}, {{0x90, 0x1c, 0x00}, {0xfc, 0xbc, 0x74}},
    {{0x94, 0x00, 0x00}, {0xfc, 0x90, 0x90}}, {{0x84, 0x00, 0x64}, {0xec, 0x8c, 0xe0}}, {{0x50, 0x00, 0x84}, {0xd4, 0x8c, 0xfc}},
    {{0x14, 0x00, 0x90}, {0xbc, 0x90, 0xfc}}, {{0x00, 0x00, 0x94}, {0x84, 0x90, 0xfc}}, {{0x00, 0x1c, 0x88}, {0x84, 0xc8, 0xfc}},
    {{0x00, 0x30, 0x64}, {0x84, 0xe0, 0xfc}}, {{0x00, 0x40, 0x30}, {0x84, 0xfc, 0xd4}}, {{0x00, 0x44, 0x00}, {0x90, 0xfc, 0x90}},
    {{0x14, 0x3c, 0x00}, {0xc8, 0xfc, 0x84}}, {{0x30, 0x38, 0x00}, {0xe0, 0xec, 0x7c}}, {{0x48, 0x2c, 0x00}, {0xfc, 0xe0, 0x70}},
};

LutImage atari_ntsc(const std::map<std::string, double>& p) {
    const double k = param(p, "luminanceCurve"), peak = param(p, "greyPeak"), gamma = param(p, "greyGamma"),
                 saturation = param(p, "saturation");
    LutImage out;
    out.width = 128;
    out.height = 1;
    out.rgba.resize(128 * 4);
    for (int hue = 0; hue < 16; ++hue)
        for (int lum = 0; lum < 8; ++lum) {
            double rgb[3];
            if (hue == 0) {
                rgb[0] = rgb[1] = rgb[2] = peak * std::pow(lum / 7.0, gamma);
            } else {
                const double f = std::log1p(lum / k) / std::log1p(7.0 / k);
                for (int c = 0; c < 3; ++c) {
                    const double dark = kAtariHueEnds[hue - 1][0][c] / 255.0, bright = kAtariHueEnds[hue - 1][1][c] / 255.0;
                    rgb[c] = dark + f * (bright - dark);
                }
                // Saturation scales the chroma (I, Q) about the colour's own luma.
                Yiq c = rgb_to_yiq(rgb[0], rgb[1], rgb[2]);
                yiq_to_rgb({c.y, c.i * saturation, c.q * saturation}, rgb);
            }
            uint8_t* px = &out.rgba[static_cast<size_t>(hue * 8 + lum) * 4];
            for (int c = 0; c < 3; ++c) px[c] = to_byte(rgb[c]);
            px[3] = 255;
        }
    append_palette_cells(out);  // the nearest-colour search tables below the palette
    return out;
}

// ---- PNG ----------------------------------------------------------------------------------

void put32(std::string& out, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xffu);
}

void chunk(std::string& out, const char* type, const std::string& data) {
    put32(out, static_cast<uint32_t>(data.size()));
    std::string body = std::string(type, 4) + data;
    out += body;
    put32(out, static_cast<uint32_t>(::crc32(::crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
}

}  // namespace

const std::vector<LutGenerator>& lut_generators() {
    static const std::vector<LutGenerator> generators = {
        {"yiq_grade",
         "Super Win the Game's colour grade: RGB -> YIQ, hue rotation, saturation, contrast, brightness, back to RGB, gamma",
         "1024x32: 32 slices of 32x32 side by side; texel (blue * 32 + red, green) holds the graded colour of "
         "(red, green, blue) / 31",
         {{"hue", -45.0, 45.0, 0.0, "Rotation of the chroma (I, Q) in degrees: tint"},
          {"saturation", 0.0, 2.0, 1.25, "Scale of the chroma: colour"},
          {"contrast", 0.5, 2.0, 1.2, "Luma contrast about mid-grey"},
          {"brightness", -0.5, 0.5, -0.03, "Luma offset"},
          {"gamma", 0.5, 2.5, 1.1, "Exponent on the decoded RGB: above 1 deepens shadows and midtones"}},
         yiq_grade},
        {"atari_ntsc",
         "The Atari 2600 NTSC palette by the rule emulators' tables follow (Stella's standard NTSC palette): hue 0 grey "
         "peak * (l / 7)^gamma; hues 1..15 from their darkest to their brightest colour (the table's) along one shared "
         "luminance curve ln(1 + l / k) / ln(1 + 7 / k); chroma scaled by saturation",
         "128 wide: row 0 the palette, texel (hue * 8 + luminance); the rows below list, per cell of a 16^3 RGB grid "
         "over [-1/16, 17/16], the entries that can be nearest there (generator/palette_cells.hpp)",
         {{"luminanceCurve", 1.0, 100.0, 9.0, "k of the colour hues' luminance curve ln(1 + l / k) / ln(1 + 7 / k): small bends it, large straightens it"},
          {"greyPeak", 0.5, 1.0, 236.0 / 255.0, "Hue 0's luminance 7 (the table's 0xec)"},
          {"greyGamma", 0.3, 1.5, 0.6, "Exponent of hue 0's luminance ramp peak * (l / 7)^gamma"},
          {"saturation", 0.0, 2.0, 1.0, "Scale of every colour's chroma (I, Q) about its luma: 1 is the published table"}},
         atari_ntsc},
    };
    return generators;
}

const LutGenerator* find_lut_generator(const std::string& name) {
    for (const auto& g : lut_generators())
        if (name == g.name) return &g;
    return nullptr;
}

Result<LutImage> generate_lut(const std::string& generator, const std::map<std::string, double>& given) {
    const LutGenerator* g = find_lut_generator(generator);
    if (!g) return make_error("unknown LUT generator '" + generator + "'");
    std::map<std::string, double> params;
    for (const LutParam& p : g->params) {
        auto it = given.find(p.name);
        const double v = it == given.end() ? p.default_value : it->second;
        if (!(v >= p.min && v <= p.max))
            return make_error("LUT param '" + p.name + "' is outside [" + std::to_string(p.min) + ", " + std::to_string(p.max) + "]");
        params[p.name] = v;
    }
    for (const auto& [name, value] : given)
        if (!params.count(name)) return make_error("LUT generator '" + generator + "' has no param '" + name + "'");
    return g->generate(params);
}

std::string encode_png(const LutImage& image) {
    std::string png("\x89PNG\r\n\x1a\n", 8);
    std::string header;
    put32(header, static_cast<uint32_t>(image.width));
    put32(header, static_cast<uint32_t>(image.height));
    header += std::string("\x08\x06\x00\x00\x00", 5);  // 8 bits, RGBA, deflate, no filter method, no interlace
    chunk(png, "IHDR", header);
    // Scanlines (filter type 0) in stored (uncompressed) deflate blocks of at most 65535 bytes.
    std::string raw;
    const size_t row = static_cast<size_t>(image.width) * 4;
    for (int y = 0; y < image.height; ++y) {
        raw += '\0';
        raw.append(reinterpret_cast<const char*>(image.rgba.data()) + y * row, row);
    }
    std::string z("\x78\x01", 2);
    for (size_t at = 0; at < raw.size() || at == 0; at += 65535) {
        const size_t n = std::min<size_t>(65535, raw.size() - at);
        const bool last = at + n >= raw.size();
        z += static_cast<char>(last ? 1 : 0);
        z += static_cast<char>(n & 0xffu);
        z += static_cast<char>((n >> 8) & 0xffu);
        z += static_cast<char>(~n & 0xffu);
        z += static_cast<char>((~n >> 8) & 0xffu);
        z.append(raw, at, n);
        if (last) break;
    }
    // zlib's Adler-32 of the uncompressed stream (the blocks stay stored: the bytes depend on no
    // compressor's version).
    put32(z, static_cast<uint32_t>(::adler32(::adler32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(raw.data()), static_cast<uInt>(raw.size()))));
    chunk(png, "IDAT", z);
    chunk(png, "IEND", "");
    return png;
}

}  // namespace crtforge
