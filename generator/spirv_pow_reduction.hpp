// pow() with a constant exponent rewritten as square roots and products (see spirv_pow_reduction.cpp).
#pragma once

#include <cstddef>

#include "crtforge/spirv_compiler.hpp"

namespace crtforge {

// Rewrites each GLSL.std.450 Pow whose exponent is a 32-bit float constant (every component the
// same) of 0.5, 1.5, 2, 2.5, 3, 4 or -0.5 as Sqrt / FMul / InverseSqrt, in place, and returns how
// many it rewrote. A module that does not parse is left as it is.
size_t reduce_constant_powers(SpirvBinary& words);

}  // namespace crtforge
