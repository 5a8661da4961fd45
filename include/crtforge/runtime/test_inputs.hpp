// Generated test inputs: the pictures the CRT shaders are rendered over. Each is a pure function of
// (name, width, height) — no randomness, no files — so goldens made from them are reproducible.
// Every input is opaque (alpha 1) and, except "hdr", within 0..1; every value is exactly a half float,
// so a consumer that uploads rgba16float sees the same picture as one that uploads rgba32float.
#pragma once

#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge {

// The native size of the "pixel_art" frame (an NES screen); other sizes are nearest-neighbour
// scalings of it, so 1024 x 896 is an exact x4.
inline constexpr int kPixelArtWidth = 256;
inline constexpr int kPixelArtHeight = 224;

// All input names, in a fixed order: color_bars, zone_plate, grey_ramp, pixel_art, hdr, mandelbrot,
// plasma, flat_grey, checker, moving_sprite.
const std::vector<std::string>& test_input_names();

// One line saying what the input is for; empty for an unknown name.
std::string test_input_doc(const std::string& name);

// Renders input `name` at width x height (each 1..kMaxImageDimension), as it is at `frame` (only
// moving inputs change with it). Errors: unknown name (the message lists the valid ones), a size
// out of range, a negative frame.
Result<Image> make_test_input(const std::string& name, int width, int height, int frame = 0);

// True for inputs that change from frame to frame (moving_sprite).
bool test_input_moves(const std::string& name);

}  // namespace crtforge
