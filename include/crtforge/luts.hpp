// Lookup textures crtforge generates from a few params (a preset's [lut.<name>] with a
// `generator`), exported as PNG files beside the shaders and bound to the passes that read them.
// Generated in double precision and stored as 8-bit RGBA, the way the files ship: every consumer
// and the reference renderer read these exact bytes.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"

namespace crtforge {

// 8-bit RGBA, row 0 at the top.
struct LutImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

struct LutParam {
    std::string name;
    double min = 0, max = 0, default_value = 0;
    std::string doc;
};

struct LutGenerator {
    const char* name;
    const char* doc;     // what it makes, and from which document
    const char* layout;  // how a shader addresses it
    std::vector<LutParam> params;
    LutImage (*generate)(const std::map<std::string, double>& params);
};

// yiq_grade: Super Win the Game's colour grade, a 32x32x32 RGB cube stored as 1024x32 (32 slices
// of 32x32 side by side: x = blue * 32 + red, y = green), each texel the RGB after an NTSC YIQ
// decode with hue, saturation, contrast, brightness and gamma ("a simplified version of Drag's
// NES Palette Generator").
// atari_ntsc: the Atari 2600's NTSC palette, 128 colours in row 0 (x = hue * 8 + luminance):
// hue 0 grey, hues 1..15 each from its darkest to its brightest colour along one shared
// luminance curve (the rule of emulators' published tables, Stella's); below it the tables of its
// nearest-colour search (palette_cells.hpp).
const std::vector<LutGenerator>& lut_generators();
const LutGenerator* find_lut_generator(const std::string& name);

// The LUT for a generator and its params (missing params take their defaults).
Result<LutImage> generate_lut(const std::string& generator, const std::map<std::string, double>& params);

// A deterministic 8-bit RGBA PNG of the image (no compression, no timestamps): what an export
// writes for a generated LUT.
std::string encode_png(const LutImage& image);

}  // namespace crtforge
