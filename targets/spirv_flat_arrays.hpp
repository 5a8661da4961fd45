// Arrays of arrays as one flat array, for languages without them (see spirv_flat_arrays.cpp).
#pragma once

#include "crtforge/spirv_compiler.hpp"

namespace crtforge::detail {

// Every array of arrays (T a[n][m]...) in the module becomes one array of its leaf type
// (T a[n * m]), indexed row-major: a full index path becomes one flat index (a constant where the
// indices are), and a path that stops at a row reads or writes the row's elements one by one. The
// same values, in types GLSL before 4.30 / ES 3.10 and Godot's shading language can declare.
// Returns how many array types it flattened (0: `words` untouched). Throws
// spirv_cross::CompilerError, naming the construct, where flattening cannot carry a use (a block
// member, whose layout the host fixes; a runtime-sized or specialisation-sized array of arrays).
size_t flatten_arrays_of_arrays(SpirvBinary& words);

}  // namespace crtforge::detail
