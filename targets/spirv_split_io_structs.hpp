// Stage inputs and outputs of struct type split into one variable per member, for languages whose
// varyings cannot be structs (see spirv_split_io_structs.cpp).
#pragma once

#include "crtforge/spirv_compiler.hpp"

namespace crtforge::detail {

// Every Input / Output variable whose type is a struct that is not a Block (`out TimebaseConfig tb`,
// not gl_PerVertex) becomes one variable per leaf member, nested structs included, named
// `<variable>_<member>[_<member>...]`, at the locations the struct's members took (the variable's
// location plus the locations of the members before), with its interpolation decorations. Loads
// and stores of the whole struct (or of a nested struct) read or write the members one by one;
// an access chain into it starts at the member's variable. Both stages of a program split alike,
// so a vertex output and the fragment input at the same location still meet.
// Returns how many variables it split (0: `words` untouched). Throws spirv_cross::CompilerError,
// naming the variable, where a use cannot be carried (an array of structs, a struct handed to a
// function or copied as a pointer).
size_t split_interface_structs(SpirvBinary& words);

}  // namespace crtforge::detail
