// Nearest-colour search tables appended to a palette LUT (see palette_cells.cpp).
#pragma once

#include "crtforge/luts.hpp"

namespace crtforge {

// The grid the tables cut RGB into: kPaletteCells^3 cells over [kPaletteCellsLow,
// kPaletteCellsLow + kPaletteCellsSpan] per channel. templates/stages/palette.glsl holds the same
// three numbers (PALETTE_CELLS...): the shader finds a colour's cell with them.
inline constexpr int kPaletteCells = 16;
inline constexpr double kPaletteCellsLow = -0.0625;
inline constexpr double kPaletteCellsSpan = 1.125;

// Appends to a one-row palette (row 0, one colour per texel, at most 256 colours) the rows that
// list, for each cell, every palette entry that can be the nearest (squared RGB distance) to some
// colour in that cell:
//   rows 1 .. H:  one texel per cell c = r + 16 g + 256 b (texel c % width, row 1 + c / width):
//                 R, G the first list texel (low, high byte), B how many list texels;
//   rows H+1 ..:  the lists, texel t at (t % width, H + 1 + t / width), four palette indices per
//                 texel in R, G, B, A, ascending, the last texel padded with the cell's first index.
// An entry p is listed unless its distance to the cell's box is larger than the largest distance
// from the box to some other entry q (then q is nearer everywhere in the box), with a margin far
// above float rounding, so a search of the list finds the entry a search of the whole palette
// finds, ties to the lowest index included.
void append_palette_cells(LutImage& palette);

}  // namespace crtforge
