// Reading and writing Image files through OpenImageIO.
//
// Pixel values are kept as the file stores them: 8/16-bit integers become value / max (0..1) with
// NO sRGB-to-linear conversion, because the generated shaders sample their input as UNORM data,
// the way engines upload textures. Float files (EXR, HDR) keep their values, above 1.0 included.
// Every failure is a one-line Diagnostic whose `file` is the path; no exception escapes.
#pragma once

#include <string>

#include "crtforge/diagnostic.hpp"
#include "crtforge/luts.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge {

// Reads the first subimage of any file OpenImageIO can read. 1 channel = grey (copied to R, G, B),
// 2 = grey + alpha, 3 = RGB, 4 = RGBA; beyond 4 only the first four are kept. Missing alpha is 1.
// Straight (unassociated) alpha is returned as stored: PNG colours are not premultiplied.
// Errors: missing file, unreadable or corrupt file, zero size, either side > kMaxImageDimension,
// deep data, and any non-finite pixel value.
Result<Image> read_image(const std::string& path);

// Writes an RGBA PNG with `bits` 8 or 16 per channel: values clamped to 0..1 and rounded to the
// nearest code. Alpha is written straight, as given.
// Writes a half-float RGBA OpenEXR (zip compression), keeping HDR values; magnitudes above the
// largest half (65504) are clamped to it rather than becoming infinity.
// Both write `path.tmp-<pid>` and rename it over `path`, so a reader never sees half a file, and
// both are byte-deterministic (no timestamps or software tags). Errors: empty or malformed image,
// non-finite pixel values, bits not 8/16, a path that cannot be written.
Status write_png(const std::string& path, const Image& image, int bits = 8);

// A LUT picture (PNG, JPEG) as 8-bit RGBA, through read_image: the texels the renders sample, each
// channel value * 255 rounded (exact for 8-bit files). crtforge's LUT picture decoder
// (crtforge/lut_file.hpp), registered by the CLI and the tests.
Result<LutImage> read_lut_picture(const std::string& path);
Status write_exr(const std::string& path, const Image& image);

}  // namespace crtforge
