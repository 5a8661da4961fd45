// A scene's geometry for one frame: where the screen sits in the display, how the source picture
// maps onto the screen, and how big each pass's output is. Shared by the generator (the source
// mapping is baked into the screen pass), every pipeline host (validate/, the reference renderer)
// and the manifest, so they all size passes the same way.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/preset.hpp"

namespace crtforge {

struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;  // pixels, origin at the top-left, rows down
};

struct PixelSize {
    int width = 0, height = 0;
};

// The screen's rectangle in a display of `display` pixels: the whole display (stretch), the largest
// centred rectangle of the screen's aspect (aspect), or that with the source's rows at a whole
// number of display rows (integer; aspect when the display is smaller than one source). The screen's
// aspect is [display] aspect, else the source's display aspect (size x pixel aspect).
PixelRect screen_rect(const Preset& preset, PixelSize display, PixelSize source, std::optional<DisplayFit> fit = {});

// How the source picture's texture coordinate follows the screen's: source uv = (screen uv - 0.5)
// * scale + 0.5. (1, 1) unless [source] fit crops or bars a picture whose aspect differs from the
// screen's; a scale above 1 shows bars (sampled outside 0..1).
std::array<double, 2> source_uv_scale(const Preset& preset);

// The pass that maps the source onto the screen (and carries that scale): the first pass whose
// output follows the viewport on both axes.
size_t screen_pass_index(const Preset& preset);

// Every pass's output size for a source of `source` texels and a screen of `screen` pixels: a
// factor of its main input's size (source), of the screen (viewport) or absolute; rounded to the
// nearest pixel, at least 1. The last pass draws the screen: its size is the screen's.
std::vector<PixelSize> pass_sizes(const Preset& preset, PixelSize source, PixelSize screen);

// An error at the pass (its [[pass]] line, field pass.<alias>.scale) whose output would be beyond
// the image memory budget at this screen, checked before a renderer allocates it; else Ok.
Status check_pass_sizes(const Preset& preset, const std::vector<PixelSize>& sizes, PixelSize screen);

}  // namespace crtforge
