// Keeps the template's local names through spirv-opt (see spirv_debug_names.cpp).
#pragma once

#include <string>

#include "crtforge/spirv_compiler.hpp"

namespace crtforge {

// Gives each SSA value a DebugValue names the name of its template local (OpName), then removes the
// NonSemantic debug info, OpLine, OpString and OpSource. A module without that debug info only
// loses its OpLine/OpString/OpSource; one that does not parse is left as it is.
void name_values_and_strip_debug_info(SpirvBinary& words);

// The template local names a module's NonSemantic debug info carries (its DebugLocalVariables, in
// order): what name_values_and_strip_debug_info gives the values, and so part of what an
// optimised module is made of besides its code ("" without that debug info).
std::string carried_local_names(const SpirvBinary& words);

// Names each value that still has none after optimisation (what spirv-opt made of an expression:
// a common subexpression, the output clamp, pow's reduction) after what it is — product, clamped,
// chosen — so SPIRV-Cross prints `vec4 clamped` rather than `vec4 _122` (it numbers repeats).
void name_unnamed_values(SpirvBinary& words);

// Removes the OpNames and decorations of ids no instruction defines any more (a lowering pass
// that replaced the values they named): spirv-val and the drivers refuse a name of nothing.
void drop_annotations_of_missing_ids(SpirvBinary& words);

}  // namespace crtforge
