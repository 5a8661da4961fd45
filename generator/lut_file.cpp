// LUT files (see crtforge/lut_file.hpp): where they may lie, and whether their bytes are a whole
// picture. The picture check walks the file's own structure (PNG chunks and zlib stream, JPEG
// markers) rather than decoding pixels: it needs no image library in the core, and it is what
// tells a truncated, padded or mislabelled file from a picture.
#include "crtforge/lut_file.hpp"

#include <array>
#include <atomic>
#include <filesystem>

#include <zlib.h>

#include "crtforge/bounded_memo.hpp"
#include "crtforge/cache.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/files.hpp"
#include "crtforge/runtime/image.hpp"

namespace fs = std::filesystem;

namespace crtforge {

namespace {

uint32_t be32(std::string_view b, size_t at) {
    return static_cast<uint32_t>(static_cast<uint8_t>(b[at])) << 24 | static_cast<uint32_t>(static_cast<uint8_t>(b[at + 1])) << 16 |
           static_cast<uint32_t>(static_cast<uint8_t>(b[at + 2])) << 8 | static_cast<uint32_t>(static_cast<uint8_t>(b[at + 3]));
}
uint32_t be16(std::string_view b, size_t at) {
    return static_cast<uint32_t>(static_cast<uint8_t>(b[at])) << 8 | static_cast<uint32_t>(static_cast<uint8_t>(b[at + 1]));
}

std::string size_error(long long width, long long height) {
    if (width <= 0 || height <= 0) return "the header declares a " + std::to_string(width) + "x" + std::to_string(height) + " picture";
    if (width > kMaxImageDimension || height > kMaxImageDimension)
        return "the picture is " + std::to_string(width) + "x" + std::to_string(height) + ", larger than the " +
               std::to_string(kMaxImageDimension) + " pixel limit";
    if (std::string over = image_budget_error(width, height); !over.empty()) return "the picture " + over;
    return {};
}

// The bytes of the filtered rows IHDR declares (each row: a filter byte, then its pixels).
uint64_t png_raw_size(uint64_t width, uint64_t height, uint64_t bits_per_pixel, bool interlaced) {
    auto rows = [&](uint64_t w, uint64_t h) { return w && h ? h * (1 + (w * bits_per_pixel + 7) / 8) : 0; };
    if (!interlaced) return rows(width, height);
    // Adam7: seven sub-images of every 8th..2nd pixel, each stored as its own rows.
    constexpr std::array<std::array<uint64_t, 4>, 7> passes = {{{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4}, {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}}};
    uint64_t total = 0;
    for (const auto& [x0, y0, dx, dy] : passes)
        total += rows(width > x0 ? (width - x0 + dx - 1) / dx : 0, height > y0 ? (height - y0 + dy - 1) / dy : 0);
    return total;
}

// Inflates `data` without keeping it: the stream must end exactly after `expected` bytes, and (for
// rows of `row_bytes`, 0 when interlaced) every row must start with a known filter type.
std::string png_stream_error(const std::string& data, uint64_t expected, uint64_t row_bytes) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) return "zlib could not start";
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    z.avail_in = static_cast<uInt>(data.size());
    std::array<unsigned char, 1 << 16> out;
    uint64_t produced = 0;
    std::string error;
    for (;;) {
        z.next_out = out.data();
        z.avail_out = out.size();
        const int rc = inflate(&z, Z_NO_FLUSH);
        const uint64_t got = out.size() - z.avail_out;
        // Only the bytes that start a row (a division per byte was a cold sweep's 2.5 %).
        for (uint64_t i = row_bytes ? (row_bytes - produced % row_bytes) % row_bytes : got; i < got; i += row_bytes)
            if (out[i] > 4) {
                error = "row " + std::to_string((produced + i) / row_bytes) + " has unknown filter type " + std::to_string(out[i]);
                break;
            }
        produced += got;
        if (!error.empty()) break;
        if (produced > expected) {
            error = "the image data holds more than the " + std::to_string(expected) + " bytes of rows IHDR declares";
            break;
        }
        if (rc == Z_STREAM_END) {
            if (produced != expected)
                error = "the image data holds " + std::to_string(produced) + " bytes of rows, IHDR declares " + std::to_string(expected);
            break;
        }
        if (rc == Z_BUF_ERROR && z.avail_in == 0) {
            error = "the image data ends early (truncated?)";
            break;
        }
        if (rc != Z_OK && rc != Z_BUF_ERROR) {
            error = std::string("the image data is not a valid zlib stream (") + (z.msg ? z.msg : "corrupt") + ")";
            break;
        }
    }
    inflateEnd(&z);
    return error;
}

std::string png_error(std::string_view b) {
    size_t at = 8;
    bool header = false, palette = false, end = false;
    uint32_t width = 0, height = 0;
    int colour = 0, bits_per_pixel = 0;
    bool interlaced = false;
    std::string data;
    while (!end) {
        if (at + 12 > b.size()) return "the file ends before its IEND chunk (truncated?)";
        const uint32_t length = be32(b, at);
        if (length > b.size() - at - 12) return "a chunk is longer than the rest of the file (truncated?)";
        const std::string type(b.substr(at + 4, 4));
        const std::string_view body = b.substr(at + 8, length);
        const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(b.data() + at + 4), length + 4);
        if (crc != be32(b, at + 8 + length)) return "chunk " + type + " fails its CRC (corrupt file)";
        at += 12 + length;
        if (!header && type != "IHDR") return "the first chunk is not IHDR";
        if (type == "IHDR") {
            if (header || length != 13) return "the IHDR chunk is malformed";
            header = true;
            width = be32(body, 0);
            height = be32(body, 4);
            if (std::string e = size_error(width, height); !e.empty()) return e;
            const int depth = static_cast<uint8_t>(body[8]);
            colour = static_cast<uint8_t>(body[9]);
            const int channels = colour == 0 || colour == 3 ? 1 : colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 0;
            const bool depth_ok = colour == 0   ? (depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16)
                                  : colour == 3 ? (depth == 1 || depth == 2 || depth == 4 || depth == 8)
                                                : (depth == 8 || depth == 16);
            if (!channels || !depth_ok)
                return "colour type " + std::to_string(colour) + " at bit depth " + std::to_string(depth) + " is not one PNG defines";
            if (body[10] != 0 || body[11] != 0 || static_cast<uint8_t>(body[12]) > 1) return "the compression, filter or interlace method is unknown";
            bits_per_pixel = channels * depth;
            interlaced = body[12] == 1;
        } else if (type == "PLTE") {
            palette = true;
        } else if (type == "IDAT") {
            data.append(body);
        } else if (type == "IEND") {
            end = true;
        } else if (type[0] >= 'A' && type[0] <= 'Z') {
            return "critical chunk " + type + " is unknown to PNG readers";
        }
    }
    if (colour == 3 && !palette) return "a palette picture lacks its PLTE chunk";
    if (data.empty()) return "there is no image data (IDAT)";
    const uint64_t row_bytes = interlaced ? 0 : 1 + (uint64_t{width} * bits_per_pixel + 7) / 8;
    return png_stream_error(data, png_raw_size(width, height, bits_per_pixel, interlaced), row_bytes);
}

// A JPEG's marker segments from after its start-of-image marker: the frame header's size once
// met (width, height), where the entropy-coded data starts (past the start-of-scan segment), or
// what is wrong. With `to_frame` it stops at the frame header (lut_picture_size needs no more).
struct JpegSegments {
    std::optional<std::pair<int, int>> size;
    size_t scan = 0;
    std::string error;
};

JpegSegments walk_jpeg(std::string_view b, bool to_frame) {
    JpegSegments out;
    auto fail = [&](const char* why) {
        out.error = why;
        return out;
    };
    size_t at = 2;
    for (;;) {
        while (at + 1 < b.size() && static_cast<uint8_t>(b[at]) == 0xff && static_cast<uint8_t>(b[at + 1]) == 0xff) ++at;  // fill bytes
        if (at + 4 > b.size()) return fail("the file ends before the picture data (truncated?)");
        if (static_cast<uint8_t>(b[at]) != 0xff) return fail("bytes stand where a marker belongs (corrupt file)");
        const uint8_t marker = static_cast<uint8_t>(b[at + 1]);
        if (marker == 0xd9) return fail("the end-of-image marker comes before the picture data");
        if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd7)) {  // markers without a length
            at += 2;
            continue;
        }
        const uint32_t length = be16(b, at + 2);
        if (length < 2 || at + 2 + length > b.size()) return fail("a marker segment is longer than the rest of the file (truncated?)");
        const bool sof = marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
        if (sof) {
            if (length < 8) return fail("the frame header is malformed");
            out.size = std::make_pair(static_cast<int>(be16(b, at + 7)), static_cast<int>(be16(b, at + 5)));
            if (to_frame) return out;
        }
        at += 2 + length;
        if (marker == 0xda) break;  // start of scan: entropy-coded data follows
    }
    if (!out.size) return fail("no frame header comes before the picture data");
    out.scan = at;
    return out;
}

std::string jpeg_error(std::string_view b) {
    const JpegSegments jpeg = walk_jpeg(b, false);
    if (!jpeg.error.empty()) return jpeg.error;
    if (std::string e = size_error(jpeg.size->first, jpeg.size->second); !e.empty()) return e;
    // In entropy-coded data a 0xff byte is stuffed (ff 00) or a restart marker, so ff d9 is the end.
    if (b.substr(jpeg.scan).find("\xff\xd9") == std::string_view::npos) return "the end-of-image marker is missing (truncated?)";
    return {};
}

}  // namespace

namespace {

// The pictures found whole in this process, by their bytes: a bezel pack's presets share a few
// large pictures, and import, the template library and export each check every LUT they meet.
BoundedMemo<bool>& whole_pictures() {
    static BoundedMemo<bool> memo(size_t{1} << 16, [](bool) { return size_t{1}; });
    return memo;
}

std::string check_picture(std::string_view bytes) {
    constexpr std::string_view png_signature("\x89PNG\r\n\x1a\n", 8);
    if (bytes.substr(0, 8) == png_signature) {
        if (std::string e = png_error(bytes); !e.empty()) return "is not a whole PNG picture: " + e;
        return {};
    }
    if (bytes.size() >= 3 && bytes.substr(0, 3) == std::string_view("\xff\xd8\xff", 3)) {
        if (std::string e = jpeg_error(bytes); !e.empty()) return "is not a whole JPEG picture: " + e;
        return {};
    }
    return "is not a PNG or JPEG picture (LUT files are PNG or JPEG, as engines load them)";
}

}  // namespace

namespace {
std::atomic<LutPictureDecoder> registered_decoder{nullptr};
}  // namespace

void set_lut_picture_decoder(LutPictureDecoder decoder) { registered_decoder = decoder; }
LutPictureDecoder lut_picture_decoder() { return registered_decoder; }

std::string lut_picture_error(std::string_view bytes) {
    const std::string key = Cache::key({"whole picture", bytes});
    if (whole_pictures().find(key)) return {};
    std::string error = check_picture(bytes);
    if (error.empty()) whole_pictures().put(key, true);
    return error;
}

Result<std::string> read_lut_file(const LutSpec& lut, const std::string& template_root) {
    const std::string field = "lut." + lut.name + ".file";
    auto fail = [&](const std::string& message) { return make_error(message, lut.where.file, lut.where.line, field); };
    if (fs::path(lut.file).is_absolute())
        return fail("'" + lut.file + "' is an absolute path; a LUT file is named relative to its preset, inside the template folder");
    const std::string path = lut_file_path(lut);
    std::error_code ec;
    const fs::path root = fs::weakly_canonical(template_root, ec);
    const fs::path resolved = ec ? fs::path() : fs::weakly_canonical(path, ec);
    if (ec) return fail("cannot resolve '" + lut.file + "': " + ec.message());
    // Component by component, so "/t/presets-other" is not taken to lie inside "/t/presets".
    auto inside = std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end());
    if (inside.first != root.end())
        return fail("'" + lut.file + "' resolves to " + resolved.string() + ", outside the template folder " + root.string());
    const fs::file_status status = fs::status(resolved, ec);
    if (!fs::exists(status)) return fail("'" + lut.file + "' does not exist");
    if (!fs::is_regular_file(status)) return fail("'" + lut.file + "' is not a regular file");
    auto bytes = read_text_file(resolved.string(), kMaxLutFileBytes);
    if (!bytes.ok()) return fail("'" + lut.file + "' " + bytes.error().message);
    if (std::string e = lut_picture_error(bytes.value()); !e.empty()) return fail("'" + lut.file + "' " + e);
    return bytes;
}

std::optional<std::pair<int, int>> lut_picture_size(std::string_view b) {
    if (b.size() >= 24 && b.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8) && b.substr(12, 4) == "IHDR")
        return std::make_pair(static_cast<int>(be32(b, 16)), static_cast<int>(be32(b, 20)));
    if (b.size() < 4 || static_cast<uint8_t>(b[0]) != 0xff || static_cast<uint8_t>(b[1]) != 0xd8) return std::nullopt;
    return walk_jpeg(b, true).size;  // the frame header's, as jpeg_error walks to it
}

}  // namespace crtforge
