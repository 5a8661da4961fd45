// clamp() as the min(max()) the GLSL specification defines it by (see spirv_clamp_lowering.cpp).
#pragma once

#include <cstddef>

#include "crtforge/spirv_compiler.hpp"

namespace crtforge {

// Rewrites each GLSL.std.450 FClamp / UClamp / SClamp / NClamp(x, lo, hi) as Min(Max(x, lo), hi)
// of the same kind, in place, unless lo and hi are 32-bit constants with lo <= hi in every
// component; returns how many it rewrote. A module that does not parse is left as it is.
size_t lower_clamps(SpirvBinary& words);

}  // namespace crtforge
