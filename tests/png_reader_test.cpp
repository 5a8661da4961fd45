// The npm package's PNG reader (decodePng in examples/webgpu/crt-webgpu.mjs), which a page uses to
// load an export's LUTs: an imported RetroArch preset ships the library's own PNGs as they are
// (palette, grey, 16-bit). PNGs of every colour type, bit depth, filter and Adam7 interlacing are
// written here byte by byte and read by it in Node, and by crtforge's own reader (OpenImageIO).
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "crtforge/runtime/image_io.hpp"
#include "tests/test_support.hpp"

using namespace crtforge;

namespace {

uint32_t crc32(const std::string& bytes) {
    uint32_t c = 0xffffffffu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

std::string be32(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

std::string chunk(const std::string& type, const std::string& data) {
    return be32(static_cast<uint32_t>(data.size())) + type + data + be32(crc32(type + data));
}

// zlib with stored (uncompressed) deflate blocks: the reader must inflate whatever a tool wrote.
std::string zlib_stored(const std::string& data) {
    std::string out = "\x78\x01";
    for (size_t at = 0; at == 0 || at < data.size(); at += 65535) {
        const size_t n = std::min<size_t>(65535, data.size() - at);
        out += char(at + n >= data.size() ? 1 : 0);
        out += {char(n & 0xff), char(n >> 8), char(~n & 0xff), char((~n >> 8) & 0xff)};
        out += data.substr(at, n);
    }
    uint32_t a = 1, b = 0;
    for (unsigned char c : data) a = (a + c) % 65521, b = (b + a) % 65521;
    return out + be32((b << 16) | a);
}

struct Png {
    int width = 13, height = 7, colour = 6, depth = 8;
    bool interlaced = false, transparency = false;
    int channels() const { return colour == 0 || colour == 3 ? 1 : colour == 4 ? 2 : colour == 2 ? 3 : 4; }
    int max() const { return colour == 3 ? 5 : (1 << depth) - 1; }  // palette: six entries
    // Sample k of pixel (x, y): a fixed scramble covering the range.
    int sample(int x, int y, int k) const { return int((uint32_t(x * 7919 + y * 104729 + k * 15485863) * 2654435761u >> 7) % uint32_t(max() + 1)); }
};

// A filtered scanline of the pixels (x0 + i * dx, y) for i < w, with filter `filter`.
std::string scanline(const Png& p, int y, int x0, int dx, int w, int filter, std::vector<uint8_t>& prior) {
    const int bits = p.channels() * p.depth, stride = (w * bits + 7) / 8, bpp = std::max(1, bits / 8);
    std::vector<uint8_t> raw(static_cast<size_t>(stride), 0);
    for (int i = 0; i < w; ++i)
        for (int k = 0; k < p.channels(); ++k) {
            const int v = p.sample(x0 + i * dx, y, k), bit = (i * p.channels() + k) * p.depth;
            if (p.depth == 16) raw[size_t(bit / 8)] = uint8_t(v >> 8), raw[size_t(bit / 8 + 1)] = uint8_t(v);
            else raw[size_t(bit / 8)] |= uint8_t(v << (8 - p.depth - bit % 8));
        }
    std::string out(1, char(filter));
    for (int i = 0; i < stride; ++i) {
        const int a = i >= bpp ? raw[size_t(i - bpp)] : 0, b = prior[size_t(i)], c = i >= bpp ? prior[size_t(i - bpp)] : 0;
        int pred = 0;
        if (filter == 1) pred = a;
        if (filter == 2) pred = b;
        if (filter == 3) pred = (a + b) / 2;
        if (filter == 4) {
            const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
            pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
        }
        out += char((raw[size_t(i)] - pred) & 0xff);
    }
    prior = raw;
    return out;
}

std::string encode(const Png& p) {
    std::string data;
    const std::vector<std::array<int, 4>> passes = p.interlaced
        ? std::vector<std::array<int, 4>>{{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4}, {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}}
        : std::vector<std::array<int, 4>>{{0, 0, 1, 1}};
    int row = 0;
    for (const auto& [x0, y0, dx, dy] : passes) {
        const int w = (p.width - x0 + dx - 1) / dx, h = (p.height - y0 + dy - 1) / dy;
        if (w <= 0 || h <= 0) continue;
        std::vector<uint8_t> prior(static_cast<size_t>((w * p.channels() * p.depth + 7) / 8), 0);
        for (int y = 0; y < h; ++y) data += scanline(p, y0 + y * dy, x0, dx, w, row++ % 5, prior);
    }
    std::string ihdr = be32(uint32_t(p.width)) + be32(uint32_t(p.height));
    ihdr += {char(p.depth), char(p.colour), 0, 0, char(p.interlaced ? 1 : 0)};
    std::string png = "\x89PNG\r\n\x1a\n" + chunk("IHDR", ihdr);
    if (p.colour == 3) {
        png += chunk("PLTE", std::string("\x00\x00\x00\xff\x00\x00\x00\xff\x00\x00\x00\xff\x80\x40\x20\xff\xff\xff", 18));
        if (p.transparency) png += chunk("tRNS", std::string("\xff\x80\x00\x40", 4));  // the last two entries opaque
    }
    return png + chunk("IDAT", zlib_stored(data)) + chunk("IEND", "");
}

std::string name_of(const Png& p) {
    return fmt::format("c{}d{}{}{}", p.colour, p.depth, p.interlaced ? "i" : "", p.transparency ? "t" : "");
}

}  // namespace

TEST_CASE("the npm package reads every PNG colour type, bit depth and interlacing as crtforge's reader does", "[wgsl][npm][png]") {
    std::vector<Png> cases;
    for (int depth : {1, 2, 4, 8, 16}) cases.push_back({13, 7, 0, depth});
    for (int depth : {1, 2, 4, 8}) cases.push_back({13, 7, 3, depth});
    for (int colour : {2, 4, 6})
        for (int depth : {8, 16}) cases.push_back({13, 7, colour, depth});
    Png palette_alpha{13, 7, 3, 4};
    palette_alpha.transparency = true;
    cases.push_back(palette_alpha);
    for (Png p : {Png{13, 7, 6, 8}, Png{13, 7, 3, 2}, Png{13, 7, 0, 16}, Png{3, 2, 2, 8}, Png{1, 1, 4, 8}}) {
        p.interlaced = true;
        cases.push_back(p);
    }
    test::TempDir dir;
    std::string files;
    for (const Png& p : cases) {
        std::ofstream(dir / (name_of(p) + ".png"), std::ios::binary) << encode(p);
        files += " '" + (dir / (name_of(p) + ".png")) + "'";
    }
    const std::string script = dir / "decode.mjs";
    std::ofstream(script) << "import { decodePng } from '" << CRTFORGE_SOURCE_DIR << "/examples/webgpu/crt-webgpu.mjs';\n"
                          << "import { readFileSync, writeFileSync } from 'fs';\n"
                          << "for (const f of process.argv.slice(2)) {\n"
                          << "  const image = await decodePng(readFileSync(f), f);\n"
                          << "  writeFileSync(f + '.raw', Buffer.from(image.data));\n"
                          << "}\n";
    auto run = test::run_command("node '" + script + "'" + files + " 2>&1");
    INFO(run.out);
    REQUIRE(run.exit_code == 0);
    for (const Png& p : cases) {
        INFO(name_of(p));
        auto expected = read_image(dir / (name_of(p) + ".png"));
        INFO((expected.ok() ? std::string() : expected.error().str()));
        REQUIRE(expected.ok());
        std::ifstream in(dir / (name_of(p) + ".png.raw"), std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        REQUIRE(bytes.size() == size_t(p.width) * size_t(p.height) * 4);
        int worst = 0;
        for (int y = 0; y < p.height; ++y)
            for (int x = 0; x < p.width; ++x)
                for (int k = 0; k < 4; ++k) {
                    const int got = static_cast<unsigned char>(bytes[size_t((y * p.width + x) * 4 + k)]);
                    const int want = int(std::lround(expected.value().pixel(x, y)[k] * 255.0f));
                    worst = std::max(worst, std::abs(got - want));
                }
        // A 16-bit sample keeps its high byte: within one step of the rounded value.
        CHECK(worst <= (p.depth == 16 ? 1 : 0));
    }
}
