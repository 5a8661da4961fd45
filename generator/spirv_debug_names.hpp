// Keeps the template's local names through spirv-opt (see spirv_debug_names.cpp).
#pragma once

#include "crtforge/spirv_compiler.hpp"

namespace crtforge {

// Gives each SSA value a DebugValue names the name of its template local (OpName), then removes the
// NonSemantic debug info, OpLine, OpString and OpSource. A module without that debug info only
// loses its OpLine/OpString/OpSource; one that does not parse is left as it is.
void name_values_and_strip_debug_info(SpirvBinary& words);

}  // namespace crtforge
