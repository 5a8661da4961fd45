// A palette's nearest-colour search, cut down to the few entries that can win in each cell of RGB.
//
// palette.frag's nearest mode compares a colour with every palette entry: 128 texel reads and
// distances per pixel for the Atari NTSC palette (55x a blit at 1280x960 on lavapipe). Over a
// 16^3 grid an entry can be the nearest somewhere in a cell for 3.6 cells' worth on average (at
// most 17), so the shader reads the cell's list instead and gets the same entry.
#include "generator/palette_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace crtforge {

namespace {

// Squared distances from point p to the nearest and the farthest point of the box [lo, hi]^3.
void box_distances(const double p[3], const double lo[3], const double hi[3], double& nearest, double& farthest) {
    nearest = farthest = 0;
    for (int k = 0; k < 3; ++k) {
        const double below = lo[k] - p[k], above = p[k] - hi[k];
        const double in = std::max({below, above, 0.0});
        const double out = std::max(std::abs(p[k] - lo[k]), std::abs(p[k] - hi[k]));
        nearest += in * in;
        farthest += out * out;
    }
}

}  // namespace

void append_palette_cells(LutImage& palette) {
    const int width = palette.width;
    if (width < 1 || width > 256 || palette.height != 1) return;
    std::vector<std::array<double, 3>> colours(static_cast<size_t>(width));
    for (int i = 0; i < width; ++i)
        for (int k = 0; k < 3; ++k) colours[static_cast<size_t>(i)][static_cast<size_t>(k)] = palette.rgba[static_cast<size_t>(i) * 4 + static_cast<size_t>(k)] / 255.0;

    constexpr int n = kPaletteCells, cells = n * n * n;
    constexpr double step = kPaletteCellsSpan / n;
    // Squared distances are at most 3 + a little; a float distance is off by some 1e-7 of that, and
    // a colour the shader puts in a neighbouring cell lies some 1e-7 outside this one.
    constexpr double kMargin = 1e-5;
    std::vector<std::vector<uint8_t>> lists(cells);
    std::vector<double> nearest(static_cast<size_t>(width)), farthest(static_cast<size_t>(width));
    for (int c = 0; c < cells; ++c) {
        const int cell[3] = {c % n, (c / n) % n, c / (n * n)};
        double lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            lo[k] = kPaletteCellsLow + cell[k] * step;
            hi[k] = lo[k] + step;
        }
        double bound = INFINITY;
        for (int i = 0; i < width; ++i) {
            box_distances(colours[static_cast<size_t>(i)].data(), lo, hi, nearest[static_cast<size_t>(i)], farthest[static_cast<size_t>(i)]);
            bound = std::min(bound, farthest[static_cast<size_t>(i)]);
        }
        std::vector<uint8_t>& list = lists[static_cast<size_t>(c)];
        for (int i = 0; i < width; ++i)
            if (nearest[static_cast<size_t>(i)] <= bound + kMargin) list.push_back(static_cast<uint8_t>(i));
        while (list.size() % 4 != 0) list.push_back(list.front());
    }

    const int header_rows = (cells + width - 1) / width;
    size_t list_texels = 0;
    for (const auto& list : lists) list_texels += list.size() / 4;
    if (list_texels > 0xffffu) return;  // a first texel must fit two bytes: the shader searches the whole palette
    const int list_rows = static_cast<int>((list_texels + static_cast<size_t>(width) - 1) / static_cast<size_t>(width));
    palette.height = 1 + header_rows + list_rows;
    palette.rgba.resize(static_cast<size_t>(width) * static_cast<size_t>(palette.height) * 4, 0);
    auto texel = [&](size_t index, int first_row) {
        return &palette.rgba[((static_cast<size_t>(first_row) + index / static_cast<size_t>(width)) * static_cast<size_t>(width) +
                              index % static_cast<size_t>(width)) * 4];
    };
    size_t next = 0;
    for (int c = 0; c < cells; ++c) {
        const std::vector<uint8_t>& list = lists[static_cast<size_t>(c)];
        uint8_t* head = texel(static_cast<size_t>(c), 1);
        head[0] = static_cast<uint8_t>(next & 0xffu);
        head[1] = static_cast<uint8_t>(next >> 8);
        head[2] = static_cast<uint8_t>(list.size() / 4);
        head[3] = 255;
        for (size_t at = 0; at < list.size(); at += 4, ++next) std::copy_n(&list[at], 4, texel(next, 1 + header_rows));
    }
}

}  // namespace crtforge
