// Pictures exchanged with the Node.js runners as files: little-endian float32 RGBA, rows top
// first, one picture after the other (the Dawn runner, check.mjs and the Godot 4 driver read and
// write this layout).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge::detail {

Status write_pictures(const std::filesystem::path& path, const std::vector<const Image*>& pictures);
Status write_pictures(const std::filesystem::path& path, const std::vector<Image>& pictures);

// `count` pictures of width x height from `path`, which must hold exactly that many bytes; else a
// Validation error naming `writer` ("the Godot 4 driver") and the sizes.
Result<std::vector<Image>> read_pictures(const std::filesystem::path& path, int width, int height, std::size_t count,
                                         const std::string& writer);

}  // namespace crtforge::detail
