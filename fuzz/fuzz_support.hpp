// What several fuzz bodies share, built once per process: the shipped template library and the
// full-screen vertex shader's SPIR-V. Failing to build either is a broken checkout, not a finding,
// so it aborts with a message rather than returning.
#pragma once

#include "crtforge/spirv_compiler.hpp"
#include "crtforge/template_library.hpp"

namespace crtforge::fuzz {

const TemplateLibrary& shipped_library();
const SpirvBinary& fullscreen_vertex();

}  // namespace crtforge::fuzz
