// Non-square matrices as the square matrices Godot's shading language has (see
// spirv_square_matrices.cpp).
#pragma once

#include "crtforge/spirv_compiler.hpp"

namespace crtforge::godot {

// Every matCxR (C columns of R rows, C != R) in the module becomes matN, N = max(C, R), its extra
// rows and columns zero, with every instruction that reads or writes a column, or multiplies by the
// matrix, padding its vector operands and shrinking its vector results: the same values, in types
// Godot can declare. Returns how many matrix types it padded (0: `words` untouched). Throws
// spirv_cross::CompilerError, naming the construct, where a matrix is used in a way the padding
// cannot carry (a uniform block member, whose layout the host fixes; a product with a smaller
// square matrix).
size_t square_matrices(SpirvBinary& words);

}  // namespace crtforge::godot
