// LUT files: the pictures a preset names with `file = "..."` (its own, or a RetroArch import's).
// They are copied into exports and loaded by engines, so they are checked where they enter
// crtforge, not where a renderer first decodes them: inside the template folder, a regular file of
// bounded size, and a whole PNG or JPEG picture within the image budget.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <string>
#include <string_view>

#include "crtforge/diagnostic.hpp"
#include "crtforge/luts.hpp"
#include "crtforge/preset.hpp"

namespace crtforge {

// How a LUT file that is not a PNG (a JPEG) becomes one at export: every target then ships PNG
// LUTs, which every engine reads and the WebGPU driver decodes itself (it has no JPEG decoder, as a
// page without an image library has none). The core has no image library: a program that has one
// (the crtforge CLI and the tests: the OpenImageIO module, the same decoder the renders use)
// registers it. Without one, a LUT file is exported as it is, under its own extension.
using LutPictureDecoder = Result<LutImage> (*)(const std::string& path);
void set_lut_picture_decoder(LutPictureDecoder decoder);
LutPictureDecoder lut_picture_decoder();

// The largest LUT file read (bytes): the corpus's largest picture is a few MB.
inline constexpr std::uintmax_t kMaxLutFileBytes = std::uintmax_t{64} << 20;

// Empty when `bytes` are a whole PNG (every chunk's CRC, IHDR, the image data inflating to exactly
// the rows IHDR declares, IEND) or a whole JPEG (its markers up to the scan, a frame header, the
// end-of-image marker) within kMaxImageDimension and the image budget; else why not.
std::string lut_picture_error(std::string_view bytes);

// A PNG's or JPEG's width and height from its header (nullopt if the bytes are neither).
std::optional<std::pair<int, int>> lut_picture_size(std::string_view bytes);

// The file of `lut` (a file LUT), relative to its preset file: refused when absolute or when it
// resolves (links followed) outside `template_root`, when it is not a regular file, is larger than
// kMaxLutFileBytes, or is not a whole picture. The error names the preset file, the LUT's line
// and the field lut.<name>.file. Returns the bytes.
Result<std::string> read_lut_file(const LutSpec& lut, const std::string& template_root);

}  // namespace crtforge
