// Image file I/O, the generated test inputs and the comparison metrics. Input files for the read
// tests are crafted byte by byte here (an uncompressed PNG writer, a PFM), so the reader is checked
// against files that do not come from the writer under test.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "tests/test_support.hpp"

namespace {

using namespace crtforge;
using Catch::Matchers::Contains;
using Bytes = std::vector<uint8_t>;

// ---- crafted files ----------------------------------------------------------------------------

uint32_t crc32(const uint8_t* data, std::size_t size, uint32_t crc = 0) {
    crc = ~crc;
    for (std::size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void put_be32(Bytes& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(v >> s));
}

void put_chunk(Bytes& png, const char* type, const Bytes& data) {
    put_be32(png, static_cast<uint32_t>(data.size()));
    Bytes body(type, type + 4);
    body.insert(body.end(), data.begin(), data.end());
    png.insert(png.end(), body.begin(), body.end());
    put_be32(png, crc32(body.data(), body.size()));
}

// A PNG whose pixel data is a zlib stream of "stored" (uncompressed) deflate blocks. `samples` are
// the raw samples, row-major, `channels` per pixel, big-endian when bits == 16.
// colour_type: 0 grey, 2 RGB, 4 grey+alpha, 6 RGBA. with_idat = false gives a header-only file.
Bytes craft_png(uint32_t width, uint32_t height, int bits, int colour_type, const Bytes& samples,
                bool with_idat = true) {
    Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    Bytes ihdr;
    put_be32(ihdr, width);
    put_be32(ihdr, height);
    ihdr.insert(ihdr.end(), {static_cast<uint8_t>(bits), static_cast<uint8_t>(colour_type), 0, 0, 0});
    put_chunk(png, "IHDR", ihdr);
    if (with_idat) {
        const std::size_t row_bytes = height ? samples.size() / height : 0;
        Bytes raw;
        for (uint32_t y = 0; y < height; ++y) {
            raw.push_back(0);  // filter type None
            raw.insert(raw.end(), samples.begin() + y * row_bytes, samples.begin() + (y + 1) * row_bytes);
        }
        Bytes z = {0x78, 0x01};
        std::size_t pos = 0;
        do {
            const std::size_t n = std::min<std::size_t>(65535, raw.size() - pos);
            const bool last = pos + n == raw.size();
            z.push_back(last ? 1 : 0);
            z.insert(z.end(), {static_cast<uint8_t>(n), static_cast<uint8_t>(n >> 8),
                               static_cast<uint8_t>(~n), static_cast<uint8_t>(~n >> 8)});
            z.insert(z.end(), raw.begin() + pos, raw.begin() + pos + n);
            pos += n;
        } while (pos < raw.size());
        uint32_t a = 1, b = 0;
        for (uint8_t v : raw) {
            a = (a + v) % 65521;
            b = (b + a) % 65521;
        }
        put_be32(z, (b << 16) | a);
        put_chunk(png, "IDAT", z);
    }
    put_chunk(png, "IEND", {});
    return png;
}

void write_bytes(const std::string& path, const Bytes& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                static_cast<std::streamsize>(bytes.size()));
}

using test::slurp;

// A little-endian RGB Portable Float Map of width x 1 pixels.
void write_pfm(const std::string& path, const std::vector<float>& rgb) {
    std::ofstream out(path, std::ios::binary);
    out << "PF\n" << rgb.size() / 3 << " 1\n-1.0\n";
    out.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size() * sizeof(float)));
}

bool no_temp_files_left(const std::string& dir) {
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().filename().string().find(".tmp-") != std::string::npos) return false;
    return true;
}

// ---- helpers ----------------------------------------------------------------------------------

// Deterministic integer-hash noise in [-amplitude, amplitude], the same for every run.
Image with_noise(Image image, double amplitude) {
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        uint32_t h = static_cast<uint32_t>(i) * 0x9E3779B1u;
        h ^= h >> 15;
        h *= 0x85EBCA77u;
        h ^= h >> 13;
        if (i % 4 != 3) image.rgba[i] += static_cast<float>(amplitude * (h / 4294967295.0 * 2.0 - 1.0));
    }
    return image;
}

Image input(const std::string& name, int w, int h) {
    auto result = make_test_input(name, w, h);
    REQUIRE(result.ok());
    return std::move(result).value();
}

float max_value(const Image& image) {
    float m = -std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
        if (i % 4 != 3) m = std::max(m, image.rgba[i]);
    return m;
}

}  // namespace

// ---- image I/O --------------------------------------------------------------------------------

TEST_CASE("8-bit PNG round trip keeps byte values and clamps out-of-range ones", "[image][io]") {
    test::TempDir dir;
    Image image = Image::make(256, 2, {0, 0, 0, 1});
    for (int x = 0; x < 256; ++x) {
        const float v = x / 255.0f;
        image.set_pixel(x, 0, {v, 1.0f - v, v, 1.0f - v});
    }
    image.set_pixel(0, 1, {1.5f, -0.25f, 3.5f, 1.0f});
    REQUIRE(write_png(dir / "a.png", image, 8).ok());
    auto back = read_image(dir / "a.png");
    REQUIRE(back.ok());
    REQUIRE(back.value().width == 256);
    REQUIRE(back.value().height == 2);
    for (int x = 0; x < 256; ++x)
        for (int c = 0; c < 4; ++c) REQUIRE(back.value().at(x, 0)[c] == Approx(image.at(x, 0)[c]).margin(1e-6));
    // Alpha below 1 is stored straight: colours are not premultiplied on the way out or in.
    CHECK(back.value().pixel(200, 0)[0] == Approx(200 / 255.0).margin(1e-6));
    CHECK(back.value().pixel(0, 1) == std::array<float, 4>{1.0f, 0.0f, 1.0f, 1.0f});
    CHECK(no_temp_files_left(dir.path()));
}

TEST_CASE("16-bit PNG keeps 1/65535 steps", "[image][io]") {
    test::TempDir dir;
    Image image = Image::make(64, 1, {0, 0, 0, 1});
    for (int x = 0; x < 64; ++x) {
        const float v = static_cast<float>((30000 + x) / 65535.0);
        image.set_pixel(x, 0, {v, v, static_cast<float>(x / 65535.0), 1.0f});
    }
    REQUIRE(write_png(dir / "b.png", image, 16).ok());
    auto back = read_image(dir / "b.png");
    REQUIRE(back.ok());
    for (int x = 0; x < 64; ++x) {
        CHECK(back.value().pixel(x, 0)[0] == Approx((30000 + x) / 65535.0).margin(1e-7));
        CHECK(back.value().pixel(x, 0)[2] == Approx(x / 65535.0).margin(1e-7));
    }
    CHECK(back.value().pixel(1, 0)[0] - back.value().pixel(0, 0)[0] == Approx(1 / 65535.0).margin(1e-7));
}

TEST_CASE("EXR keeps HDR values that PNG clamps", "[image][io]") {
    test::TempDir dir;
    Image image = Image::make(4, 3, {0.25f, 0.5f, 3.5f, 1.0f});
    image.set_pixel(1, 2, {0.1f, 1e6f, -2.0f, 0.5f});
    REQUIRE(write_exr(dir / "c.exr", image).ok());
    auto exr = read_image(dir / "c.exr");
    REQUIRE(exr.ok());
    CHECK(exr.value().pixel(0, 0) == std::array<float, 4>{0.25f, 0.5f, 3.5f, 1.0f});
    CHECK(exr.value().pixel(1, 2)[0] == Approx(0.1).epsilon(1e-3));  // half precision
    CHECK(exr.value().pixel(1, 2)[1] == 65504.0f);                     // clamped to the largest half
    CHECK(exr.value().pixel(1, 2)[2] == -2.0f);
    CHECK(exr.value().pixel(1, 2)[3] == 0.5f);

    REQUIRE(write_png(dir / "c.png", image, 8).ok());
    auto png = read_image(dir / "c.png");
    REQUIRE(png.ok());
    CHECK(png.value().pixel(0, 0)[2] == 1.0f);
}

TEST_CASE("written files are byte-identical across writes", "[image][io][determinism]") {
    test::TempDir dir;
    const Image image = input("mandelbrot", 96, 64);
    for (const char* ext : {"png8", "png16", "exr"}) {
        INFO(ext);
        const std::string a = dir / (std::string(ext) + "-a"), b = dir / (std::string(ext) + "-b");
        for (const std::string& path : {a, b}) {
            const Status s = std::string(ext) == "exr" ? write_exr(path, image)
                                                       : write_png(path, image, std::string(ext) == "png8" ? 8 : 16);
            REQUIRE(s.ok());
        }
        const std::string first = slurp(a);
        CHECK(first.size() > 100);
        CHECK(first == slurp(b));
        // Nothing time- or host-dependent in the metadata.
        CHECK(first.find("DateTime") == std::string::npos);
        CHECK(first.find("Software") == std::string::npos);
        CHECK(first.find("OpenImageIO") == std::string::npos);
        // No timestamp either (OIIO puts one in EXR's capDate unless told otherwise).
        char today[32];
        const std::time_t now = std::time(nullptr);
        std::strftime(today, sizeof today, "%Y:%m:%d", std::localtime(&now));
        CHECK(first.find(today) == std::string::npos);
    }
    // Overwriting an existing file works too (rename replaces it).
    REQUIRE(write_png(dir / "png8-a", input("checker", 8, 8), 8).ok());
    CHECK(slurp(dir / "png8-a") != slurp(dir / "png8-b"));
    CHECK(no_temp_files_left(dir.path()));
}

TEST_CASE("grey, grey+alpha, RGB and RGBA files expand to RGBA", "[image][io]") {
    test::TempDir dir;
    write_bytes(dir / "grey.png", craft_png(2, 1, 8, 0, {0, 51}));
    write_bytes(dir / "grey_alpha.png", craft_png(1, 1, 8, 4, {102, 128}));
    write_bytes(dir / "rgb.png", craft_png(1, 2, 8, 2, {255, 0, 51, 0, 255, 102}));
    write_bytes(dir / "rgba.png", craft_png(1, 1, 8, 6, {204, 102, 51, 0}));
    write_bytes(dir / "grey16.png", craft_png(1, 1, 16, 0, {0x00, 0x01}));

    auto grey = read_image(dir / "grey.png");
    REQUIRE(grey.ok());
    CHECK(grey.value().pixel(0, 0) == std::array<float, 4>{0, 0, 0, 1});
    for (int c = 0; c < 3; ++c) CHECK(grey.value().pixel(1, 0)[c] == Approx(0.2));
    CHECK(grey.value().pixel(1, 0)[3] == 1.0f);

    auto grey_alpha = read_image(dir / "grey_alpha.png");
    REQUIRE(grey_alpha.ok());
    CHECK(grey_alpha.value().pixel(0, 0)[0] == Approx(0.4));  // not premultiplied by 128/255
    CHECK(grey_alpha.value().pixel(0, 0)[2] == Approx(0.4));
    CHECK(grey_alpha.value().pixel(0, 0)[3] == Approx(128 / 255.0));

    auto rgb = read_image(dir / "rgb.png");
    REQUIRE(rgb.ok());
    CHECK(rgb.value().pixel(0, 0)[0] == 1.0f);  // row 0 = top
    CHECK(rgb.value().pixel(0, 0)[2] == Approx(0.2));
    CHECK(rgb.value().pixel(0, 1)[1] == 1.0f);
    CHECK(rgb.value().pixel(0, 1)[2] == Approx(0.4));
    CHECK(rgb.value().pixel(0, 1)[3] == 1.0f);

    auto rgba = read_image(dir / "rgba.png");
    REQUIRE(rgba.ok());
    // Fully transparent, yet the colour survives: straight alpha, no sRGB decoding.
    CHECK(rgba.value().pixel(0, 0)[0] == Approx(0.8));
    CHECK(rgba.value().pixel(0, 0)[1] == Approx(0.4));
    CHECK(rgba.value().pixel(0, 0)[2] == Approx(0.2));
    CHECK(rgba.value().pixel(0, 0)[3] == 0.0f);

    auto grey16 = read_image(dir / "grey16.png");
    REQUIRE(grey16.ok());
    CHECK(grey16.value().pixel(0, 0)[1] == Approx(1 / 65535.0).margin(1e-9));
}

TEST_CASE("read_image reports every kind of bad file in one line naming it", "[image][io][errors]") {
    test::TempDir dir;
    const auto expect_error = [](const std::string& path, const std::string& fragment) {
        auto result = read_image(path);
        REQUIRE_FALSE(result.ok());
        INFO(result.error().str());
        CHECK(result.error().file == path);
        CHECK_THAT(result.error().str(), Contains(fragment));
        CHECK(result.error().str().find('\n') == std::string::npos);
    };
    expect_error(dir / "missing.png", "not found");
    expect_error(dir.path(), "directory");

    write_bytes(dir / "noise.png", {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e', 0, 1, 2, 3});
    expect_error(dir / "noise.png", "cannot read");

    Bytes truncated = craft_png(16, 16, 8, 2, Bytes(16 * 16 * 3, 7));
    truncated.resize(truncated.size() / 2);
    write_bytes(dir / "truncated.png", truncated);
    expect_error(dir / "truncated.png", "cannot read");

    // A valid header and a token IDAT (libpng wants one before it reports the size); the size
    // check must refuse it before any pixel is read.
    write_bytes(dir / "huge.png", craft_png(20000, 1, 8, 0, {}));
    expect_error(dir / "huge.png", "16384");

    // PNG forbids a zero width; whichever layer notices, it must be a clean error.
    write_bytes(dir / "empty.png", craft_png(0, 0, 8, 0, {}, false));
    CHECK_FALSE(read_image(dir / "empty.png").ok());

    write_pfm(dir / "nan.pfm", {0.5f, std::numeric_limits<float>::quiet_NaN(), 0.5f, 1, 1, 1});
    expect_error(dir / "nan.pfm", "non-finite");
}

TEST_CASE("float files keep values above 1", "[image][io]") {
    test::TempDir dir;
    write_pfm(dir / "hdr.pfm", {3.5f, 0.25f, 12.0f});
    auto hdr = read_image(dir / "hdr.pfm");
    REQUIRE(hdr.ok());
    CHECK(hdr.value().pixel(0, 0) == std::array<float, 4>{3.5f, 0.25f, 12.0f, 1.0f});
}

TEST_CASE("writers refuse bad images and paths without leaving files", "[image][io][errors]") {
    test::TempDir dir;
    const Image good = Image::make(2, 2, {0.5f, 0.5f, 0.5f, 1});
    for (const Status& s : {write_png("/nonexistent-dir/x.png", good, 8), write_exr("/nonexistent-dir/x.exr", good)}) {
        REQUIRE_FALSE(s.ok());
        CHECK(s.error().file.find("/nonexistent-dir/") == 0);
    }
    CHECK_FALSE(write_png(dir / "empty.png", Image{}, 8).ok());
    CHECK_FALSE(write_exr(dir / "empty.exr", Image{}).ok());
    CHECK_FALSE(write_png(dir / "bits.png", good, 12).ok());
    Image bad = good;
    bad.rgba[5] = std::numeric_limits<float>::infinity();
    CHECK_FALSE(write_exr(dir / "inf.exr", bad).ok());
    Image malformed = good;
    malformed.rgba.pop_back();
    CHECK_FALSE(write_png(dir / "malformed.png", malformed, 8).ok());
    CHECK(std::filesystem::is_empty(dir.path()));
}

// ---- generated test inputs --------------------------------------------------------------------

TEST_CASE("every test input has its size, is opaque, finite and deterministic", "[image][inputs]") {
    REQUIRE(test_input_names().size() == 10);
    for (const std::string& name : test_input_names()) {
        INFO(name);
        CHECK_FALSE(test_input_doc(name).empty());
        const Image a = input(name, 67, 45), b = input(name, 67, 45);
        REQUIRE(a.width == 67);
        REQUIRE(a.height == 45);
        REQUIRE(a.consistent());
        CHECK(a.rgba == b.rgba);
        bool opaque = true, finite = true, in_unit = true;
        for (std::size_t i = 0; i < a.rgba.size(); ++i) {
            finite = finite && std::isfinite(a.rgba[i]);
            if (i % 4 == 3) opaque = opaque && a.rgba[i] == 1.0f;
            else in_unit = in_unit && a.rgba[i] >= 0.0f && a.rgba[i] <= 1.0f;
        }
        CHECK(opaque);
        CHECK(finite);
        if (name != "hdr") CHECK(in_unit);
    }
}

TEST_CASE("test input errors: unknown name lists the names, bad sizes", "[image][inputs][errors]") {
    auto unknown = make_test_input("smpte", 8, 8);
    REQUIRE_FALSE(unknown.ok());
    for (const std::string& name : test_input_names()) CHECK_THAT(unknown.error().str(), Contains(name));
    CHECK_FALSE(make_test_input("checker", 0, 8).ok());
    CHECK_FALSE(make_test_input("checker", 8, 16385).ok());
    CHECK(test_input_doc("smpte").empty());
}

TEST_CASE("test inputs have their key properties", "[image][inputs]") {
    SECTION("zone plate: 1.0 at the centre, radially symmetric") {
        const Image z = input("zone_plate", 128, 96);
        const int cx = 64, cy = 48;
        CHECK(z.pixel(cx, cy)[0] == 1.0f);
        for (int dy = 0; dy < 48; dy += 3)
            for (int dx = 0; dx < 48; dx += 5) {
                const float v = z.pixel(cx + dx, cy + dy)[0];
                CHECK(z.pixel(cx - dx, cy + dy)[0] == v);
                CHECK(z.pixel(cx + dx, cy - dy)[0] == v);
                CHECK(z.pixel(cx + dy, cy + dx)[0] == v);  // swapping the axes: only r matters
            }
    }
    SECTION("grey ramp: 0 to 1, monotonic, 8 steps below") {
        const Image g = input("grey_ramp", 200, 20);
        CHECK(g.pixel(0, 0)[0] == 0.0f);
        CHECK(g.pixel(199, 0)[0] == 1.0f);
        std::vector<float> steps;
        for (int x = 1; x < 200; ++x) {
            CHECK(g.pixel(x, 0)[0] > g.pixel(x - 1, 0)[0]);
            CHECK(g.pixel(x, 15)[0] >= g.pixel(x - 1, 15)[0]);
        }
        for (int x = 0; x < 200; ++x) steps.push_back(g.pixel(x, 15)[0]);
        steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
        CHECK(steps.size() == 8);
        CHECK(g.pixel(5, 5)[1] == g.pixel(5, 5)[0]);
    }
    SECTION("hdr: highlights above 1, peak 4.0") {
        const Image h = input("hdr", 320, 180);
        CHECK(max_value(h) > 1.0f);
        CHECK(max_value(h) == Approx(4.0));
    }
    SECTION("pixel art at 1024x896 is the 256x224 frame scaled x4, nearest") {
        const Image small = input("pixel_art", kPixelArtWidth, kPixelArtHeight);
        const Image big = input("pixel_art", 1024, 896);
        bool exact = true;
        for (int y = 0; y < 896 && exact; ++y)
            for (int x = 0; x < 1024 && exact; ++x) exact = big.pixel(x, y) == small.pixel(x / 4, y / 4);
        CHECK(exact);
        // Hard edges: a palette look, not a gradient.
        std::vector<std::array<float, 4>> colours(small.rgba.size() / 4);
        for (std::size_t i = 0; i < colours.size(); ++i) colours[i] = small.pixel(static_cast<int>(i % 256), static_cast<int>(i / 256));
        std::sort(colours.begin(), colours.end());
        colours.erase(std::unique(colours.begin(), colours.end()), colours.end());
        CHECK(colours.size() >= 8);
        CHECK(colours.size() <= 16);
    }
    SECTION("flat grey is 0.5 everywhere") {
        const Image f = input("flat_grey", 33, 17);
        for (std::size_t i = 0; i < f.rgba.size(); ++i) CHECK(f.rgba[i] == (i % 4 == 3 ? 1.0f : 0.5f));
    }
    SECTION("colour bars: 75% white first, 75% blue last") {
        const Image c = input("color_bars", 700, 300);
        CHECK(c.pixel(10, 10) == std::array<float, 4>{0.75f, 0.75f, 0.75f, 1});
        CHECK(c.pixel(150, 10) == std::array<float, 4>{0.75f, 0.75f, 0, 1});
        CHECK(c.pixel(690, 10) == std::array<float, 4>{0, 0, 0.75f, 1});
        CHECK(c.pixel(10, 210) == std::array<float, 4>{0, 0, 0.75f, 1});  // reverse strip
        CHECK(c.pixel(200, 290) == std::array<float, 4>{1, 1, 1, 1});     // 100% white block
    }
    SECTION("checker alternates every pixel") {
        const Image k = input("checker", 4, 4);
        CHECK(k.pixel(0, 0)[0] == 1.0f);
        CHECK(k.pixel(1, 0)[0] == 0.0f);
        CHECK(k.pixel(1, 1)[0] == 1.0f);
    }
    SECTION("mandelbrot: the main cardioid is black, the outside is coloured") {
        const Image m = input("mandelbrot", 350, 250);  // 0.01 per pixel, x = 0 at -2.5
        CHECK(m.pixel(230, 125) == std::array<float, 4>{0, 0, 0, 1});  // c = (-0.2, 0)
        CHECK(max_value(m) > 0.5f);
        CHECK(m.pixel(0, 0) != m.pixel(230, 125));
    }
}

// ---- comparison -------------------------------------------------------------------------------

TEST_CASE("identical images compare perfectly", "[image][compare]") {
    for (const char* name : {"plasma", "hdr", "checker"}) {
        const Image a = input(name, 64, 48);
        auto m = compare_images(a, a);
        REQUIRE(m.ok());
        CHECK(m.value().max_abs == 0);
        CHECK(m.value().rmse == 0);
        CHECK(m.value().psnr == 100);
        CHECK(m.value().ssim == 1);
    }
}

TEST_CASE("a constant offset of 0.1 gives max_abs 0.1, rmse 0.1, psnr 20", "[image][compare]") {
    const Image ref = Image::make(40, 30, {0.4f, 0.4f, 0.4f, 1});
    Image test = Image::make(40, 30, {0.5f, 0.5f, 0.5f, 0.2f});  // alpha differs: ignored
    auto m = compare_images(test, ref);
    REQUIRE(m.ok());
    CHECK(m.value().max_abs == Approx(0.1).epsilon(1e-5));
    CHECK(m.value().rmse == Approx(0.1).epsilon(1e-5));
    CHECK(m.value().psnr == Approx(20.0).epsilon(1e-5));
    // Flat images: only the luminance term of SSIM is left, (2xy + C1) / (x^2 + y^2 + C1).
    CHECK(m.value().ssim == Approx((2 * 0.4 * 0.5 + 1e-4) / (0.16 + 0.25 + 1e-4)).epsilon(1e-5));

    test.set_pixel(17, 23, {0.5f, 0.9f, 0.5f, 1});
    auto worst = compare_images(test, ref);
    REQUIRE(worst.ok());
    CHECK(worst.value().max_abs == Approx(0.5).epsilon(1e-5));
    CHECK(worst.value().worst_x == 17);
    CHECK(worst.value().worst_y == 23);
}

TEST_CASE("comparison errors: size mismatch names both sizes, non-finite values", "[image][compare][errors]") {
    auto mismatch = compare_images(Image::make(64, 32), Image::make(32, 32));
    REQUIRE_FALSE(mismatch.ok());
    CHECK_THAT(mismatch.error().str(), Contains("64x32") && Contains("32x32"));
    CHECK_FALSE(compare_images(Image{}, Image{}).ok());
    Image nan = Image::make(4, 4, {0, 0, 0, 1});
    nan.rgba[4] = std::numeric_limits<float>::quiet_NaN();
    auto bad = compare_images(nan, Image::make(4, 4, {0, 0, 0, 1}));
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().kind == ErrorKind::Validation);
}

TEST_CASE("SSIM falls as noise grows, and ignores HDR overshoot", "[image][compare]") {
    const Image ref = input("plasma", 96, 80);
    auto light = compare_images(with_noise(ref, 0.02), ref);
    auto heavy = compare_images(with_noise(ref, 0.2), ref);
    REQUIRE(light.ok());
    REQUIRE(heavy.ok());
    CHECK(light.value().ssim < 1.0);
    CHECK(heavy.value().ssim < light.value().ssim);
    CHECK(heavy.value().psnr < light.value().psnr);
    CHECK(heavy.value().ssim > 0.0);

    // Values above 1 clamp before SSIM: 3.0 vs 1.0 is a large max_abs but no structural change.
    const Image one = Image::make(32, 32, {1, 1, 1, 1}), three = Image::make(32, 32, {3, 3, 3, 1});
    auto hdr = compare_images(three, one);
    REQUIRE(hdr.ok());
    CHECK(hdr.value().max_abs == 2.0);
    CHECK(hdr.value().ssim == 1.0);

    // Tiny images use one global window.
    auto tiny = compare_images(with_noise(input("checker", 6, 6), 0.1), input("checker", 6, 6));
    REQUIRE(tiny.ok());
    CHECK(tiny.value().ssim < 1.0);
    CHECK(tiny.value().ssim > 0.5);
}

TEST_CASE("diff heat-map: black where equal, red at tolerance, white beyond 4x", "[image][compare]") {
    const Image ref = Image::make(4, 1, {0.5f, 0.5f, 0.5f, 1});
    Image test = ref;
    test.set_pixel(1, 0, {0.51f, 0.5f, 0.5f, 1});  // exactly the tolerance
    test.set_pixel(2, 0, {0.5f, 0.5f, 0.54f, 1});  // 4x
    test.set_pixel(3, 0, {0.5f, 0.0f, 0.5f, 1});   // far beyond
    const Image map = diff_heatmap(test, ref, 0.01);
    REQUIRE(map.width == 4);
    CHECK(map.pixel(0, 0) == std::array<float, 4>{0, 0, 0, 1});
    CHECK(map.pixel(1, 0)[0] == Approx(1.0).margin(1e-3));
    CHECK(map.pixel(1, 0)[1] == Approx(0.0).margin(2e-3));
    CHECK(map.pixel(1, 0)[2] == Approx(0.0).margin(2e-3));
    CHECK(map.pixel(2, 0)[0] == Approx(1.0));
    CHECK(map.pixel(2, 0)[1] == Approx(1.0).margin(2e-3));
    CHECK(map.pixel(2, 0)[2] == Approx(1.0).margin(2e-3));
    CHECK(map.pixel(3, 0) == std::array<float, 4>{1, 1, 1, 1});

    // Different sizes: the map covers both and marks the uncovered part white.
    const Image wider = diff_heatmap(Image::make(6, 1, {0.5f, 0.5f, 0.5f, 1}), ref, 0.01);
    REQUIRE(wider.width == 6);
    CHECK(wider.pixel(0, 0) == std::array<float, 4>{0, 0, 0, 1});
    CHECK(wider.pixel(5, 0) == std::array<float, 4>{1, 1, 1, 1});
}
