// The image reader (crtforge/runtime/image_io.hpp) on PNG and OpenEXR files, the formats crtforge
// writes and documents. read_image takes a path, so the bytes go to a file of this process's own,
// named .png or .exr after the magic number, as a user's file would be.
//
// Two kinds of input are skipped, to keep the fuzzer on parsing rather than on memory traffic:
//  - a header claiming more than kMaxFuzzPixels: the reader rightly accepts up to the image memory
//    budget (kMaxImagePixels), but allocating and zeroing ~1 GiB before OpenImageIO finds the data
//    missing costs a second per input (hostile_input_test covers the budget itself);
//  - an OpenEXR header attribute longer than the file: OpenEXR allocates whatever it claims.
// Anything else, OpenImageIO's fall-back probing of its other formats included, runs as it would.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "crtforge/runtime/image_io.hpp"
#include "fuzz/fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;

constexpr unsigned long long kMaxFuzzPixels = 256 * 256;

uint32_t big_endian(const uint8_t* p) { return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3]; }
int32_t little_endian(const uint8_t* p) {
    return static_cast<int32_t>(uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24);
}

// PNG: width and height are the first fields of the IHDR chunk, which must come first.
bool png_fits(const uint8_t* data, size_t size) {
    if (size < 24) return true;
    return static_cast<unsigned long long>(big_endian(data + 16)) * big_endian(data + 20) <= kMaxFuzzPixels;
}

// OpenEXR: after magic and version, attributes "name\0type\0" int32 size, value; an empty name
// ends the header. dataWindow is a box2i (xmin, ymin, xmax, ymax).
bool exr_fits(const uint8_t* data, size_t size) {
    size_t at = 8;
    auto string_end = [&](size_t from) { return static_cast<const uint8_t*>(std::memchr(data + from, 0, size - from)); };
    while (at < size && data[at] != 0) {
        const uint8_t* name_end = string_end(at);
        if (!name_end) return true;
        const size_t type_at = static_cast<size_t>(name_end - data) + 1;
        const uint8_t* type_end = type_at < size ? string_end(type_at) : nullptr;
        if (!type_end || static_cast<size_t>(type_end - data) + 5 > size) return true;
        const std::string name(reinterpret_cast<const char*>(data + at), reinterpret_cast<const char*>(name_end));
        const size_t value_at = static_cast<size_t>(type_end - data) + 5;
        const int32_t length = little_endian(type_end + 1);
        if (length < 0 || static_cast<size_t>(length) > size - value_at) return false;
        if (name == "dataWindow" && length == 16) {
            const long long width = 1LL + little_endian(data + value_at + 8) - little_endian(data + value_at);
            const long long height = 1LL + little_endian(data + value_at + 12) - little_endian(data + value_at + 4);
            if (width > 0 && height > 0 && static_cast<unsigned long long>(width) * height > kMaxFuzzPixels) return false;
        }
        at = value_at + static_cast<size_t>(length);
    }
    return true;
}

// One scratch file per extension, removed when the process exits normally.
struct ScratchFiles {
    std::string base = (fs::temp_directory_path() / ("crtforge-fuzz-" + std::to_string(::getpid()))).string();
    ~ScratchFiles() {
        std::error_code ec;
        for (const char* ext : {".png", ".exr"}) fs::remove(base + ext, ec);
    }
};

}  // namespace

int crtforge_fuzz_image_reader(const uint8_t* data, size_t size) {
    static const uint8_t png_magic[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const uint8_t exr_magic[] = {0x76, 0x2f, 0x31, 0x01};
    const char* extension = nullptr;
    if (size >= sizeof png_magic && std::memcmp(data, png_magic, sizeof png_magic) == 0) {
        if (!png_fits(data, size)) return -1;
        extension = ".png";
    } else if (size >= sizeof exr_magic && std::memcmp(data, exr_magic, sizeof exr_magic) == 0) {
        if (!exr_fits(data, size)) return -1;
        extension = ".exr";
    } else {
        return -1;  // neither format
    }

    static const ScratchFiles scratch;
    const std::string path = scratch.base + extension;
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) {
            std::perror(path.c_str());
            std::abort();  // a full or read-only temp dir would otherwise look like a clean run
        }
    }
    (void)crtforge::read_image(path);
    return 0;
}
