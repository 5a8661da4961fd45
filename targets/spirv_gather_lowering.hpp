// textureGather as four reads, for languages without it (see spirv_gather_lowering.cpp).
#pragma once

#include "crtforge/spirv_compiler.hpp"

namespace crtforge::detail {

// Every OpImageGather of a float 2D texture, without offsets, becomes four level-0 reads at the
// centres of the 2 x 2 texels of its footprint, the asked component of each, in gather's order
// (i0j1, i1j1, i1j0, i0j0): the same texels, each read whole by a sampler that returns a texel
// centre as it is, in what GLSL 3.30, ES 3.00 and Godot can print. Other gathers are left for
// SPIRV-Cross to refuse by name. Returns how many it lowered (0: `words` untouched).
size_t lower_texture_gathers(SpirvBinary& words);

}  // namespace crtforge::detail
