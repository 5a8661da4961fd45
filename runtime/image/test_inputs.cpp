// The generated test inputs. Each generator works in double precision from pixel centres and
// depends only on (width, height), so the same request always gives the same floats.
#include "crtforge/runtime/test_inputs.hpp"

#include "crtforge/runtime/image_io.hpp"  // kMaxImageDimension: inputs are never larger than a readable file

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>

namespace crtforge {
namespace {

using Rgb = std::array<double, 3>;
constexpr double kPi = std::numbers::pi;

void put(Image& image, int x, int y, const Rgb& c) {
    image.set_pixel(x, y, {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]), 1.0f});
}

Rgb mix(const Rgb& a, const Rgb& b, double t) {
    return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

// Cosine colour palette a + b*cos(2*pi*(t + phase)): smooth, periodic, fully saturated cycles.
Rgb cosine_palette(double t, const Rgb& phase) {
    Rgb c;
    for (int i = 0; i < 3; ++i) c[i] = 0.5 + 0.5 * std::cos(2.0 * kPi * (t + phase[i]));
    return c;
}

// ---- color_bars -------------------------------------------------------------------------------
// SMPTE ECR 1-1978 layout: 7 bars at 75% over the top 2/3, a strip of reverse "castellation" bars,
// then -I / 100% white / +Q / black / PLUGE blocks. Values are the nominal RGB, not a signal level.
Image color_bars(int w, int h) {
    const Rgb bars[7] = {{.75, .75, .75}, {.75, .75, 0}, {0, .75, .75}, {0, .75, 0},
                         {.75, 0, .75},   {.75, 0, 0},   {0, 0, .75}};
    const Rgb reverse[7] = {{0, 0, .75}, {0, 0, 0}, {.75, 0, .75}, {0, 0, 0},
                            {0, .75, .75}, {0, 0, 0}, {.75, .75, .75}};
    const Rgb minus_i = {0.0, 0.13, 0.29}, plus_q = {0.20, 0.0, 0.42}, white = {1, 1, 1}, black = {0, 0, 0};
    const int top_end = (h * 2) / 3, strip_end = (h * 3) / 4;
    Image image = Image::make(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int bar = static_cast<int>(static_cast<int64_t>(x) * 7 / w);
            Rgb c;
            if (y < top_end) {
                c = bars[bar];
            } else if (y < strip_end) {
                c = reverse[bar];
            } else {
                // Bottom row: the first 5 bar widths hold -I, white, +Q and black (5/4 bar each);
                // under bar 5 a PLUGE of 0%, 3.5% and 7.5%: steps that a crushed black level hides.
                const double pos = (x + 0.5) * 7.0 / w;
                if (pos < 1.25) c = minus_i;
                else if (pos < 2.5) c = white;
                else if (pos < 3.75) c = plus_q;
                else if (pos < 5.0 + 1.0 / 3) c = black;
                else if (pos < 5.0 + 2.0 / 3) c = {0.035, 0.035, 0.035};
                else if (pos < 6.0) c = {0.075, 0.075, 0.075};
                else c = black;
            }
            put(image, x, y, c);
        }
    }
    return image;
}

// ---- zone_plate -------------------------------------------------------------------------------
// 0.5 + 0.5*cos(k*r^2), r in pixels from the centre pixel (w/2, h/2). The local frequency is
// d(k r^2)/dr = 2 k r rad/pixel; k = pi / max(w, h) makes it pi (Nyquist) at the farther edge
// midpoint, r = max(w, h)/2. Beyond that (corners, and nowhere else in a square) it aliases.
Image zone_plate(int w, int h) {
    const double k = kPi / std::max(w, h);
    const int cx = w / 2, cy = h / 2;
    Image image = Image::make(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double r2 = double(x - cx) * (x - cx) + double(y - cy) * (y - cy);
            const double v = 0.5 + 0.5 * std::cos(k * r2);
            put(image, x, y, {v, v, v});
        }
    }
    return image;
}

// ---- grey_ramp --------------------------------------------------------------------------------
// Top half: x/(w-1), exactly 0 at the left column and 1 at the right. Bottom half: 8 equal steps
// 0, 1/7, ..., 1 — where banding and the scanline response to each level are easy to see.
Image grey_ramp(int w, int h) {
    Image image = Image::make(w, h);
    const int split = h >= 2 ? h / 2 : h;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double v;
            if (y < split) v = w > 1 ? double(x) / (w - 1) : 0.0;
            else v = double(static_cast<int64_t>(x) * 8 / w) / 7.0;
            put(image, x, y, {v, v, v});
        }
    }
    return image;
}

// ---- pixel_art --------------------------------------------------------------------------------
// An original 256x224 side-scroller frame drawn into an 8-bit RGB canvas with an NES-like palette:
// sky, HUD text, clouds, a hill, a bush, floating bricks and "?" blocks, a pipe, ground blocks and
// a 16x16 character. Each element uses 2-3 colours plus black, with hard pixel edges.
struct Rgb8 {
    uint8_t r, g, b;
};
constexpr Rgb8 kSky{92, 148, 252}, kWhite{252, 252, 252}, kBlack{0, 0, 0}, kBrick{200, 76, 12},
    kBrickLight{252, 188, 176}, kGreen{0, 168, 0}, kLightGreen{128, 208, 16}, kDarkGreen{0, 88, 0},
    kOrange{252, 152, 56}, kDarkBrown{136, 20, 0}, kCloudShade{60, 188, 252}, kRed{216, 40, 0},
    kSkin{252, 188, 140};

class Canvas {
public:
    Canvas() { pixels_.fill(kSky); }
    void set(int x, int y, Rgb8 c) {
        if (x >= 0 && x < kPixelArtWidth && y >= 0 && y < kPixelArtHeight) pixels_[y * kPixelArtWidth + x] = c;
    }
    Rgb8 get(int x, int y) const { return pixels_[y * kPixelArtWidth + x]; }

private:
    std::array<Rgb8, kPixelArtWidth * kPixelArtHeight> pixels_;
};

// 5x7 glyphs in 8x8 cells, '#' = ink.
struct Glyph {
    char ch;
    const char* rows[7];
};
constexpr Glyph kFont[] = {
    {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'T', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'F', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {'O', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'G', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".###."}},
    {'E', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {'W', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "##.##", "#...#"}},
    {'L', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {'D', {"####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."}},
    {'I', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'M', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {'x', {".....", ".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#"}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
};

void draw_text(Canvas& canvas, int column, int row_y, const char* text) {
    for (int i = 0; text[i] != '\0'; ++i) {
        for (const Glyph& glyph : kFont) {
            if (glyph.ch != text[i]) continue;
            for (int gy = 0; gy < 7; ++gy)
                for (int gx = 0; gx < 5; ++gx)
                    if (glyph.rows[gy][gx] == '#') canvas.set((column + i) * 8 + 1 + gx, row_y + gy, kWhite);
        }
    }
}

// Draws a character bitmap; '.' is transparent, other characters pick a colour via `colour`.
void draw_bitmap(Canvas& canvas, int x0, int y0, const char* const* rows, int height,
                 const std::function<Rgb8(char)>& colour) {
    for (int y = 0; y < height; ++y)
        for (int x = 0; rows[y][x] != '\0'; ++x)
            if (rows[y][x] != '.') canvas.set(x0 + x, y0 + y, colour(rows[y][x]));
}

// A puffy shape (cloud or bush): three overlapping discs with a flat base, a black outline and a
// shaded band along the lower edge of each lobe.
void draw_puff(Canvas& canvas, int cx, int cy, Rgb8 fill, Rgb8 shade) {
    const auto inside = [&](int x, int y) {
        if (y > cy + 8) return false;
        const int lobes[3][3] = {{cx - 13, cy + 2, 9}, {cx, cy - 3, 12}, {cx + 13, cy + 2, 9}};
        for (const auto& l : lobes)
            if ((x - l[0]) * (x - l[0]) + (y - l[1]) * (y - l[1]) <= l[2] * l[2]) return true;
        return false;
    };
    for (int y = cy - 17; y <= cy + 10; ++y) {
        for (int x = cx - 24; x <= cx + 24; ++x) {
            if (inside(x, y)) {
                canvas.set(x, y, inside(x, y + 3) ? fill : shade);
            } else if (inside(x - 1, y) || inside(x + 1, y) || inside(x, y - 1) || inside(x, y + 1)) {
                canvas.set(x, y, kBlack);
            }
        }
    }
}

// A ground block: bevelled stone, light top-left edge, black bottom-right edge.
void draw_ground_block(Canvas& canvas, int x0, int y0) {
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            Rgb8 c = kBrick;
            if (x == 15 || y == 15 || (x == 8 && y < 8) || (y == 7 && x > 8)) c = kBlack;
            else if (x == 0 || y == 0 || (x == 9 && y < 7)) c = kBrickLight;
            canvas.set(x0 + x, y0 + y, c);
        }
}

// A floating brick: running-bond courses with black mortar and a light top line.
void draw_brick_block(Canvas& canvas, int x0, int y0) {
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const int course = y / 4, joint = (course % 2 == 0) ? 0 : 8;
            Rgb8 c = kBrick;
            if (y == 0) c = kBrickLight;
            else if (y % 4 == 3 || x % 16 == joint || x == (joint + 15) % 16) c = kBlack;
            canvas.set(x0 + x, y0 + y, c);
        }
}

void draw_question_block(Canvas& canvas, int x0, int y0) {
    static const char* const mark[10] = {"..DDDD..", ".DD..DD.", ".DD..DD.", ".....DD.", "....DD..",
                                         "...DD...", "...DD...", "........", "...DD...", "...DD..."};
    const auto on_mark = [&](int x, int y) {
        return x >= 0 && x < 8 && y >= 0 && y < 10 && mark[y][x] == 'D';
    };
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            Rgb8 c = kOrange;
            if (x == 15 || y == 15) c = kBlack;
            else if (x == 0 || y == 0) c = kDarkBrown;
            else if ((x == 2 || x == 13) && (y == 2 || y == 13)) c = kBlack;  // rivets
            else if (on_mark(x - 4, y - 3)) c = kDarkBrown;
            else if (on_mark(x - 5, y - 4)) c = kBlack;  // drop shadow of the mark
            canvas.set(x0 + x, y0 + y, c);
        }
}

void draw_pipe(Canvas& canvas, int x0, int top, int bottom) {
    // Lip: 32 wide, 14 tall; body: 28 wide. Light stripe at the left, dark at the right.
    const auto shade = [](int x, int width) {
        if (x == 0 || x == width - 1) return kBlack;
        if (x < 4 || (x > 6 && x < 9)) return kLightGreen;
        if (x > width - 8) return kDarkGreen;
        return kGreen;
    };
    for (int y = top; y <= bottom; ++y) {
        const bool lip = y < top + 14;
        const int left = lip ? x0 : x0 + 2, width = lip ? 32 : 28;
        for (int x = 0; x < width; ++x) {
            Rgb8 c = shade(x, width);
            if (y == top || y == top + 13) c = kBlack;
            canvas.set(left + x, y, c);
        }
    }
}

void draw_hill(Canvas& canvas, int cx, int base, int half_width, int height) {
    const auto inside = [&](int x, int y) {
        const double dx = double(x - cx) / half_width, dy = double(base - y) / height;
        return y < base && dy >= 0 && dx * dx + dy * dy <= 1.0;
    };
    for (int y = base - height - 1; y < base; ++y)
        for (int x = cx - half_width - 1; x <= cx + half_width + 1; ++x) {
            if (inside(x, y)) canvas.set(x, y, kGreen);
            else if (inside(x, y + 1) || inside(x - 1, y) || inside(x + 1, y)) canvas.set(x, y, kBlack);
        }
    // Two dark ridges, the classic hill "eyes".
    for (int i = 0; i < 2; ++i)
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 2; ++x) canvas.set(cx - 5 + i * 8 + x, base - height + 10 + y, kDarkGreen);
}

Canvas draw_pixel_art_frame() {
    Canvas canvas;
    draw_text(canvas, 3, 16, "CRTFORGE");
    draw_text(canvas, 18, 16, "WORLD");
    draw_text(canvas, 25, 16, "TIME");
    draw_text(canvas, 3, 24, "004250");
    draw_text(canvas, 11, 24, "x07");
    draw_text(canvas, 19, 24, "1-1");
    draw_text(canvas, 26, 24, "321");

    draw_puff(canvas, 64, 62, kWhite, kCloudShade);
    draw_puff(canvas, 176, 50, kWhite, kCloudShade);
    draw_hill(canvas, 48, 192, 44, 36);
    draw_puff(canvas, 140, 183, kLightGreen, kGreen);  // a bush is a green cloud on the ground

    draw_question_block(canvas, 80, 128);
    draw_brick_block(canvas, 112, 128);
    draw_question_block(canvas, 128, 128);
    draw_brick_block(canvas, 144, 128);
    draw_question_block(canvas, 160, 128);
    draw_brick_block(canvas, 176, 128);
    draw_question_block(canvas, 128, 64);

    draw_pipe(canvas, 208, 160, 191);
    for (int bx = 0; bx < kPixelArtWidth; bx += 16) {
        draw_ground_block(canvas, bx, 192);
        draw_ground_block(canvas, bx, 208);
    }

    static const char* const hero[16] = {
        ".......K........", "......KRK.......", ".....KKKKKK.....", "....KSSSSSSK....",
        "...KSSKSSKSSK...", "...KSSKSSKSSK...", "...KSSSSSSSSK...", "....KSSRRSSK....",
        ".....KKKKKK.....", "....KRRRRRRK....", "...KRRSRRSRRK...", "..KSKRRRRRRKSK..",
        "..KKKRRRRRRKKK..", ".....KKK.KKK....", "....KKKK.KKKK...", "....KKKK.KKKK..."};
    draw_bitmap(canvas, 72, 176, hero, 16, [](char c) {
        return c == 'R' ? kRed : c == 'S' ? kSkin : kBlack;
    });
    return canvas;
}

Image pixel_art(int w, int h) {
    static const Canvas frame = draw_pixel_art_frame();
    Image image = Image::make(w, h);
    for (int y = 0; y < h; ++y) {
        const int sy = static_cast<int>(static_cast<int64_t>(y) * kPixelArtHeight / h);
        for (int x = 0; x < w; ++x) {
            const int sx = static_cast<int>(static_cast<int64_t>(x) * kPixelArtWidth / w);
            const Rgb8 c = frame.get(sx, sy);
            put(image, x, y, {c.r / 255.0, c.g / 255.0, c.b / 255.0});
        }
    }
    return image;
}

// ---- hdr --------------------------------------------------------------------------------------
// A dark-to-mid gradient with emissive highlights as a bloom pass sees them: discs (1 px
// anti-aliased rim), point lights and thin lines, values up to exactly 4.0 at the brightest disc.
Image hdr(int w, int h) {
    struct Disc {
        double x, y, radius;  // fractions of width, height, min(width, height)
        Rgb colour;
    };
    const Disc discs[] = {{0.25, 0.30, 0.045, {4.0, 4.0, 4.0}},   {0.72, 0.25, 0.025, {1.5, 2.0, 3.0}},
                          {0.55, 0.62, 0.070, {2.5, 1.2, 0.4}},   {0.12, 0.80, 0.008, {1.2, 1.2, 1.2}},
                          {0.22, 0.80, 0.008, {1.8, 1.6, 1.2}},   {0.32, 0.80, 0.008, {2.4, 2.0, 1.5}},
                          {0.42, 0.80, 0.008, {3.0, 2.6, 2.0}}};
    const double scale = std::min(w, h);
    Image image = Image::make(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double px = x + 0.5, py = y + 0.5, t = py / h;
            Rgb c = mix({0.02, 0.02, 0.04}, {0.30, 0.24, 0.20}, t);
            c[2] += 0.06 * px / w;
            for (const Disc& d : discs) {
                const double dist = std::hypot(px - d.x * w, py - d.y * h);
                const double cover = std::clamp(d.radius * scale - dist + 0.5, 0.0, 1.0);
                if (cover > 0) c = mix(c, d.colour, cover);
            }
            // A horizontal 1-px line at 3.0 and a diagonal neon line at 2.0.
            const double line_y = 0.45 * h;
            if (px > 0.1 * w && px < 0.9 * w) c = mix(c, {3.0, 3.0, 3.0}, std::clamp(1.0 - std::abs(py - line_y), 0.0, 1.0));
            const double ax = 0.65 * w, ay = 0.92 * h, bx = 0.92 * w, by = 0.55 * h;
            const double len = std::hypot(bx - ax, by - ay);
            const double along = ((px - ax) * (bx - ax) + (py - ay) * (by - ay)) / (len * len);
            if (along >= 0 && along <= 1) {
                const double dist = std::abs((px - ax) * (by - ay) - (py - ay) * (bx - ax)) / len;
                c = mix(c, {0.4, 2.0, 1.2}, std::clamp(1.0 - dist, 0.0, 1.0));
            }
            put(image, x, y, c);
        }
    }
    return image;
}

// ---- mandelbrot -------------------------------------------------------------------------------
// Escape time over the view centred at (-0.75, 0) spanning at least 3.5 x 2.5 (the whole set),
// square pixels. Smooth (continuous) iteration count n + 1 - log2(log|z|) with bailout |z| > 256,
// through a rainbow cosine palette; points that never escape in 200 iterations are black.
Image mandelbrot(int w, int h) {
    constexpr int kMaxIterations = 200;
    constexpr double kBailout2 = 256.0 * 256.0;
    const double step = std::max(3.5 / w, 2.5 / h);
    Image image = Image::make(w, h);
    for (int y = 0; y < h; ++y) {
        const double ci = (h / 2.0 - (y + 0.5)) * step;  // row 0 is the top: +imaginary
        for (int x = 0; x < w; ++x) {
            const double cr = -0.75 + ((x + 0.5) - w / 2.0) * step;
            double zr = 0, zi = 0;
            int n = 0;
            for (; n < kMaxIterations && zr * zr + zi * zi <= kBailout2; ++n) {
                const double t = zr * zr - zi * zi + cr;
                zi = 2.0 * zr * zi + ci;
                zr = t;
            }
            if (n == kMaxIterations) {
                put(image, x, y, {0, 0, 0});
                continue;
            }
            const double smooth = n + 1.0 - std::log2(0.5 * std::log(zr * zr + zi * zi));
            // log2 spreads the few-iteration background and the many-iteration filaments over
            // similar stretches of the rainbow (hue cycles about once per 8x more iterations).
            const double hue = 0.6 + 0.35 * std::log2(std::max(smooth, 1.0));
            put(image, x, y, cosine_palette(hue, {0.0, 1.0 / 3.0, 2.0 / 3.0}));
        }
    }
    return image;
}

// ---- plasma -----------------------------------------------------------------------------------
// Demoscene plasma at t = 1: sin(x) + sin(y) + sin(x + y) + sin(radial distance), on coordinates
// normalised to the image so any size shows the same picture, mapped through a cosine palette.
Image plasma(int w, int h) {
    constexpr double t = 1.0;
    Image image = Image::make(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double u = (x + 0.5) / w * 16.0, v = (y + 0.5) / h * 12.0;
            const double cx = u - 8.0 + 4.0 * std::sin(t / 3.0), cy = v - 6.0 + 4.0 * std::cos(t / 2.0);
            const double sum = std::sin(u + t) + std::sin(v * 0.8 + 2.0 * t) + std::sin((u + v) * 0.5 + t) +
                               std::sin(std::sqrt(cx * cx + cy * cy) * 2.0 + t);
            // sum is in [-4, 4]: about 1.2 palette cycles across that range, the banded classic look.
            put(image, x, y, cosine_palette(0.3 * sum + 0.5, {0.0, 1.0 / 3.0, 2.0 / 3.0}));
        }
    }
    return image;
}

// ---- simple fills -----------------------------------------------------------------------------
Image flat_grey(int w, int h) { return Image::make(w, h, {0.5f, 0.5f, 0.5f, 1.0f}); }

Image checker(int w, int h) {
    Image image = Image::make(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double v = (x + y) % 2 == 0 ? 1.0 : 0.0;
            put(image, x, y, {v, v, v});
        }
    return image;
}

// ---- moving_sprite ------------------------------------------------------------------------------

// The pixel-art frame with a bright 16 x 16 sprite (in 256 x 224 units) crossing it left to right
// at 3 units a frame, wrapping, 8 units below the middle: a scene in motion for feedback and
// history (trails, persistence). Frame 0 has the sprite at the left edge.
Image moving_sprite(int w, int h, int frame) {
    Image image = pixel_art(w, h);
    const double sx = w / 256.0, sy = h / 224.0;
    const int unit_x = ((frame * 3) % (256 + 16)) - 16;  // enters from off-screen
    const int unit_y = 112 + 8 - 8;
    for (int y = 0; y < h; ++y) {
        const double v = (y + 0.5) / sy - unit_y;
        if (v < 0 || v >= 16) continue;
        for (int x = 0; x < w; ++x) {
            const double u = (x + 0.5) / sx - unit_x;
            if (u < 0 || u >= 16) continue;
            // A white body with an orange core: bright in every channel, and a colour a tint acts on.
            const bool core = u >= 4 && u < 12 && v >= 4 && v < 12;
            image.set_pixel(x, y, core ? std::array<float, 4>{1.0f, 0.55f, 0.1f, 1.0f} : std::array<float, 4>{1.0f, 1.0f, 1.0f, 1.0f});
        }
    }
    return image;
}

struct Generator {
    std::string name;
    std::string doc;
    Image (*make)(int, int);
    Image (*make_frame)(int, int, int) = nullptr;  // inputs that move: the picture at a frame
};

const std::vector<Generator>& generators() {
    static const std::vector<Generator> list = {
        {"color_bars", "75% SMPTE bars over reverse bars and -I/white/+Q/black/PLUGE blocks: colour fidelity.", color_bars},
        {"zone_plate", "circular zone plate 0.5+0.5cos(kr^2), Nyquist at the far edge: aliasing and ringing.", zone_plate},
        {"grey_ramp", "linear 0->1 ramp (top half) over an 8-step staircase (bottom half): tone response.", grey_ramp},
        {"pixel_art", "256x224 NES-style frame (nearest-scaled to other sizes): the look CRT shaders are for.", pixel_art},
        {"hdr", "dark-to-mid gradient with highlight discs and lines up to 4.0: bloom and HDR handling.", hdr},
        {"mandelbrot", "escape-time Mandelbrot around (-0.75, 0), smooth palette, 200 iterations: fine detail.", mandelbrot},
        {"plasma", "demoscene sine plasma at t = 1 through a cosine palette: smooth saturated gradients.", plasma},
        {"flat_grey", "uniform 0.5 grey: isolates the scanline and mask pattern for period measurements.", flat_grey},
        {"checker", "1-pixel black/white checkerboard, white at (0, 0): worst case for filtering.", checker},
        {"moving_sprite", "the pixel-art frame with a 16x16 sprite crossing it at 3 units a frame: motion for feedback and history.",
         nullptr, moving_sprite},
    };
    return list;
}

}  // namespace

const std::vector<std::string>& test_input_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const Generator& g : generators()) out.push_back(g.name);
        return out;
    }();
    return names;
}

std::string test_input_doc(const std::string& name) {
    for (const Generator& g : generators())
        if (g.name == name) return g.doc;
    return {};
}

bool test_input_moves(const std::string& name) {
    for (const Generator& g : generators())
        if (g.name == name) return g.make_frame != nullptr;
    return false;
}

Result<Image> make_test_input(const std::string& name, int width, int height, int frame) {
    for (const Generator& g : generators()) {
        if (g.name != name) continue;
        if (width < 1 || height < 1 || width > kMaxImageDimension || height > kMaxImageDimension) {
            return make_error("test input size " + std::to_string(width) + "x" + std::to_string(height) +
                                  " is out of range (each side 1.." + std::to_string(kMaxImageDimension) + ")",
                              {}, 0, "input");
        }
        if (const std::string over = image_budget_error(width, height); !over.empty())
            return make_error("test input size " + std::to_string(width) + "x" + std::to_string(height) + " " + over, {}, 0, "input");
        if (frame < 0) return make_error("frame " + std::to_string(frame) + " is negative", {}, 0, "frame");
        Image image = g.make_frame ? g.make_frame(width, height, frame) : g.make(width, height);
        // Every value exactly a half float: consumers that upload inputs as rgba16float (Dawn
        // without float32-filterable) then see the same picture as the float ones.
        for (float& v : image.rgba) v = static_cast<float>(static_cast<_Float16>(v));
        return image;
    }
    std::string known;
    for (const std::string& n : test_input_names()) known += (known.empty() ? "" : ", ") + n;
    return make_error("unknown test input '" + name + "' (known: " + known + ")", {}, 0, "input");
}

}  // namespace crtforge
