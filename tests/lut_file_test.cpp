// LUT files (issue 29, hostile input): a preset's `file = "..."` picture is checked where it enters
// crtforge — inside the template folder, a regular file, a whole PNG or JPEG within the image
// budget — and one preset's bad file leaves the rest of its folder usable.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <vector>

#include <sys/stat.h>
#include <zlib.h>

#include <catch2/catch.hpp>

#include "crtforge/files.hpp"
#include "crtforge/lut_file.hpp"
#include "crtforge/luts.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/template_library.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;
namespace fs = std::filesystem;

namespace {

// A real PNG: the Atari palette table crtforge generates.
std::string palette_png() {
    auto lut = generate_lut("atari_ntsc", {});
    REQUIRE(lut.ok());
    return encode_png(lut.value());
}

// A PNG chunk: length, type, body, CRC.
std::string png_chunk(const std::string& type, const std::string& body) {
    std::string out;
    for (int k = 0; k < 4; ++k) out += static_cast<char>(body.size() >> (24 - 8 * k));
    const std::string typed = type + body;
    out += typed;
    const auto crc = static_cast<uint32_t>(::crc32(::crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(typed.data()),
                                                   static_cast<uInt>(typed.size())));
    for (int k = 0; k < 4; ++k) out += static_cast<char>(crc >> (24 - 8 * k));
    return out;
}

// An 8-bit RGBA PNG of width x height grey pixels whose rows carry `filters[row]` (0 past its end)
// as their filter byte: made by hand, so a row can carry a filter type no PNG writer would.
std::string rgba_png(uint32_t width, uint32_t height, const std::vector<uint8_t>& filters) {
    std::string raw;
    for (uint32_t y = 0; y < height; ++y) {
        raw += static_cast<char>(y < filters.size() ? filters[y] : 0);
        raw.append(size_t{width} * 4, static_cast<char>(0x80));
    }
    uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
    std::string packed(packed_size, '\0');
    REQUIRE(compress(reinterpret_cast<Bytef*>(packed.data()), &packed_size, reinterpret_cast<const Bytef*>(raw.data()),
                     static_cast<uLong>(raw.size())) == Z_OK);
    packed.resize(packed_size);
    std::string header;
    for (uint32_t v : {width, height})
        for (int k = 0; k < 4; ++k) header += static_cast<char>(v >> (24 - 8 * k));
    header += std::string("\x08\x06\x00\x00\x00", 5);
    return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", header) + png_chunk("IDAT", packed) + png_chunk("IEND", "");
}

// A baseline JPEG's structure around `scan` entropy bytes: SOI, a frame header of width x height,
// a scan header, the scan, EOI. Enough for the structural check (no pixels are decoded).
std::string jpeg_bytes(int width, int height, const std::string& scan = std::string("\x12\xff\x00\x34", 4), bool end = true) {
    std::string b("\xff\xd8", 2);
    b += std::string("\xff\xe0\x00\x04\x00\x00", 6);  // an APP0 segment of two bytes
    b += std::string("\xff\xc0\x00\x0b\x08", 5);
    b += static_cast<char>(height >> 8);
    b += static_cast<char>(height & 0xff);
    b += static_cast<char>(width >> 8);
    b += static_cast<char>(width & 0xff);
    b += std::string("\x01\x01\x11\x00", 4);
    b += std::string("\xff\xda\x00\x08\x01\x01\x00\x00\x3f\x00", 10);
    b += scan;
    if (end) b += std::string("\xff\xd9", 2);
    return b;
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// An overlay folder with preset `name` sampling LUT `file` as its palette.
std::string palette_preset(const std::string& name, const std::string& file, const std::string& base = "") {
    if (!base.empty()) return "name = \"" + name + "\"\ndoc = \"d\"\nbase = \"" + base + "\"\n";
    return "name = \"" + name + "\"\ndoc = \"d\"\n\n[lut.ntsc]\nfile = \"" + file +
           "\"\nfilter = \"nearest\"\n\n[[pass]]\nalias = \"palette\"\nfilter = \"nearest\"\n[pass.textures]\npalette = \"lut:ntsc\"\n"
           "[pass.stages.palette]\npaletteMode = \"nearest\"\npaletteSize = 128\n";
}

}  // namespace

TEST_CASE("a LUT picture is checked whole: truncated, corrupt, mislabelled or oversized bytes are refused", "[lut-file][hostile]") {
    const std::string png = palette_png();
    CHECK(lut_picture_error(png).empty());
    // Cut anywhere, the PNG is refused (a cut inside IEND's CRC as much as one in the header).
    for (size_t cut = 0; cut < png.size(); cut += std::max<size_t>(1, png.size() / 97)) {
        INFO(cut);
        CHECK_FALSE(lut_picture_error(png.substr(0, cut)).empty());
    }
    CHECK_FALSE(lut_picture_error(png.substr(0, png.size() - 1)).empty());
    // One flipped bit in the image data fails its chunk's CRC.
    std::string flipped = png;
    flipped[png.find("IDAT") + 10] ^= 0x04;
    CHECK_THAT(lut_picture_error(flipped), Catch::Contains("CRC"));
    CHECK_THAT(lut_picture_error("P6\n4 4\n255\n"), Catch::Contains("not a PNG or JPEG"));
    CHECK_THAT(lut_picture_error(""), Catch::Contains("not a PNG or JPEG"));

    CHECK(lut_picture_error(jpeg_bytes(64, 32)).empty());
    CHECK_THAT(lut_picture_error(jpeg_bytes(64, 32, std::string("\x12\xff\x00\x34", 4), false)), Catch::Contains("end-of-image"));
    CHECK_THAT(lut_picture_error(jpeg_bytes(64, 32).substr(0, 12)), Catch::Contains("truncated"));
    CHECK_THAT(lut_picture_error(jpeg_bytes(kMaxImageDimension + 1, 8)), Catch::Contains("pixel limit"));
    CHECK_THAT(lut_picture_error(jpeg_bytes(8192, 8193)), Catch::Contains("budget"));
    CHECK_THAT(lut_picture_error(jpeg_bytes(0, 8)), Catch::Contains("0x8"));

    // The size a form's layout is checked against comes from the same walk of the markers.
    CHECK(lut_picture_size(jpeg_bytes(64, 32)) == std::make_pair(64, 32));
    std::string filled = jpeg_bytes(1024, 32);
    filled.insert(2, "\xff\xff\xff");  // fill bytes before a marker
    CHECK(lut_picture_size(filled) == std::make_pair(1024, 32));
    CHECK(lut_picture_error(filled).empty());
    CHECK_FALSE(lut_picture_size(jpeg_bytes(64, 32).substr(0, 12)));  // cut before the frame header
    CHECK_FALSE(lut_picture_size("P6\n4 4\n255\n"));
    CHECK(lut_picture_size(png).has_value());
}

TEST_CASE("a PNG's header is held to its image data: size, rows and filter bytes", "[lut-file][hostile]") {
    // The palette PNG's IHDR claims a picture twice as tall: its rows run short.
    std::string png = palette_png();
    const size_t ihdr = png.find("IHDR");
    const uint32_t height = static_cast<uint8_t>(png[ihdr + 10]) << 8 | static_cast<uint8_t>(png[ihdr + 11]);
    png[ihdr + 10] = static_cast<char>((height * 2) >> 8);
    png[ihdr + 11] = static_cast<char>((height * 2) & 0xff);
    // Keep the CRC right, so it is the row count that is caught.
    const std::string body = png.substr(ihdr, 17);
    const auto crc = static_cast<uint32_t>(::crc32(::crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(body.data()), 17));
    for (int k = 0; k < 4; ++k) png[ihdr + 17 + k] = static_cast<char>(crc >> (24 - 8 * k));
    CHECK_THAT(lut_picture_error(png), Catch::Contains("IHDR declares"));

    // Rows of 4001 bytes inflate across many of the check's 64 KiB buffers: a row's filter byte
    // is found wherever a buffer boundary falls, and only row starts are read as filter bytes.
    std::vector<uint8_t> filters(40, 0);
    for (uint32_t y = 0; y < 40; ++y) filters[y] = static_cast<uint8_t>(y % 5);  // every known type
    CHECK(lut_picture_error(rgba_png(1000, 40, filters)).empty());
    for (uint32_t bad : {0u, 16u, 17u, 33u, 39u}) {
        INFO(bad);
        std::vector<uint8_t> broken = filters;
        broken[bad] = 5;
        CHECK_THAT(lut_picture_error(rgba_png(1000, 40, broken)), Catch::Contains("row " + std::to_string(bad) + " has unknown filter type 5"));
    }
}

TEST_CASE("a preset's LUT file lies inside its template folder and is a regular file", "[lut-file][hostile]") {
    test::TempDir dir;
    const fs::path overlay = dir / "overlay", presets = overlay / "presets";
    write_bytes(presets / "mine/ntsc.png", palette_png());
    write_bytes(dir / "outside.png", palette_png());
    write_bytes((presets / "mine.toml").string(), palette_preset("mine", "mine/ntsc.png"));
    {
        auto lib = TemplateLibrary::load(overlay.string());
        REQUIRE(lib.ok());
        auto mine = lib.value()->lookup_preset("mine");
        INFO((mine.ok() ? std::string() : mine.error().str()));
        CHECK(mine.ok());
    }
    fs::create_symlink(dir / "outside.png", presets / "mine/link.png");
    REQUIRE(::mkfifo((presets / "mine/fifo.png").c_str(), 0600) == 0);
    fs::create_symlink("/dev/zero", presets / "mine/zero.png");
    write_bytes(presets / "mine/text.png", "not a picture\n");
    write_bytes(presets / "mine/cut.png", palette_png().substr(0, 300));
    struct Case {
        std::string file, says;
    } cases[] = {
        {"../../outside.png", "outside the template folder"},
        {dir / "outside.png", "absolute path"},
        {"mine/link.png", "outside the template folder"},
        {"mine/zero.png", "outside the template folder"},
        {"mine/fifo.png", "not a regular file"},
        {"mine/text.png", "not a PNG or JPEG"},
        {"mine/cut.png", "not a whole PNG"},
        {"mine/none.png", "does not exist"},
        {"mine", "not a regular file"},
    };
    for (const Case& c : cases) {
        INFO(c.file);
        write_bytes((presets / "mine.toml").string(), palette_preset("mine", c.file));
        const auto start = std::chrono::steady_clock::now();
        auto lib = TemplateLibrary::load(overlay.string());
        REQUIRE(lib.ok());
        auto mine = lib.value()->lookup_preset("mine");
        REQUIRE_FALSE(mine.ok());
        CHECK_THAT(mine.error().file, Catch::EndsWith("presets/mine.toml"));
        CHECK(mine.error().line == 4);
        CHECK(mine.error().field == "lut.ntsc.file");
        CHECK_THAT(mine.error().message, Catch::Contains(c.says));
        // Refused from the file's kind, never by reading it: a FIFO or /dev/zero would not end.
        CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(30));
    }
}

TEST_CASE("a picture reader refuses a FIFO instead of waiting on it", "[lut-file][hostile][image]") {
    test::TempDir dir;
    const std::string fifo = dir / "input.png";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    auto image = read_image(fifo);
    REQUIRE_FALSE(image.ok());
    CHECK_THAT(image.error().message, Catch::Contains("not a regular file"));
}

TEST_CASE("one broken preset in a folder is that preset's error, and the others export", "[lut-file][hostile][cli]") {
    test::TempDir dir;
    const fs::path overlay = dir / "overlay", presets = overlay / "presets";
    write_bytes(presets / "good/ntsc.png", palette_png());
    write_bytes(presets / "bad/ntsc.png", palette_png().substr(0, 200));
    write_bytes((presets / "good.toml").string(), palette_preset("good", "good/ntsc.png"));
    write_bytes((presets / "bad.toml").string(), palette_preset("bad", "bad/ntsc.png"));
    write_bytes((presets / "bad-child.toml").string(), palette_preset("bad-child", "", "bad"));
    const std::string templates = "--templates '" + overlay.string() + "' ";

    const std::string out = dir / "out";
    auto good = test::run_crtforge(templates + "export -q --preset good --target glsl330 --out '" + out + "'");
    INFO(good.err);
    CHECK(good.exit_code == 0);
    CHECK(fs::exists(out + "/glsl330/good.frag"));
    auto copied = read_text_file(out + "/luts/good.ntsc.png");
    CHECK((copied.ok() && copied.value() == palette_png()));

    // Naming the broken preset, or one derived from it: its own error, and nothing written.
    const std::string out2 = dir / "out2";
    auto bad = test::run_crtforge(templates + "export -q --preset bad --target glsl330 --out '" + out2 + "'");
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.err, Catch::Contains("presets/bad.toml:4") && Catch::Contains("lut.ntsc.file") && Catch::Contains("not a whole PNG"));
    CHECK_FALSE(fs::exists(out2));
    auto child = test::run_crtforge(templates + "export -q --preset bad-child --target glsl330 --out '" + out2 + "'");
    CHECK(child.exit_code == 2);
    CHECK_THAT(child.err, Catch::Contains("presets/bad-child.toml:3") && Catch::Contains("base preset 'bad' does not load"));
    CHECK_FALSE(fs::exists(out2));

    // A command over every preset stops, saying each broken one on its own line.
    auto all = test::run_crtforge(templates + "export -q --target glsl330 --out '" + out2 + "'");
    CHECK(all.exit_code == 2);
    CHECK_THAT(all.err, Catch::Contains("presets/bad.toml:4") && Catch::Contains("presets/bad-child.toml:3"));
    CHECK(std::count(all.err.begin(), all.err.end(), '\n') == 2);
    CHECK_FALSE(fs::exists(out2));
    auto listed = test::run_crtforge(templates + "list presets");
    CHECK(listed.exit_code == 2);
}
