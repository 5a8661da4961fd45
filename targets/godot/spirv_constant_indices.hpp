// Vectors and matrices indexed by constants only, for Godot 3 (see spirv_constant_indices.cpp).
#pragma once

#include "crtforge/spirv_compiler.hpp"

namespace crtforge::godot {

// Whether the module indexes a vector or a matrix by a value that is not a constant (v[i]).
bool has_variable_vector_index(const SpirvBinary& words);

// A module that does has every loop marked for unrolling and fully unrolled by spirv-opt, which
// turns a loop counter's indices into constants; `words` is left as it was when nothing needs it
// or spirv-opt fails. Returns whether it unrolled.
bool with_loops_unrolled_for_constant_indices(SpirvBinary& words);

}  // namespace crtforge::godot
