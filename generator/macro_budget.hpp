// A bound on what the C preprocessor would make of a shader, checked before glslang runs it: a
// chain of macros each using the one before twice (`#define A2 (A1+A1)`, forty deep) expands to
// 2^40 tokens, and glslang's preprocessor would take all the memory and time there is to write them.
#pragma once

#include <string>

#include "crtforge/diagnostic.hpp"

namespace crtforge::detail {

// Most tokens one macro may expand to, and the whole source after expansion (a generous ceiling:
// the corpus's largest passes, koko-aio's and Mega Bezel's, come to well under a tenth of it).
inline constexpr double kMaxMacroTokens = 4.0e6;

// An error at the `#define` (file and line as glslang would name them, `#line` directives
// followed) whose expansion, or at the line where the source's total, passes kMaxMacroTokens.
Status check_macro_expansion(const std::string& source, const std::string& name);

}  // namespace crtforge::detail
