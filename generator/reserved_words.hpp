// Names a param may not take because some target language reserves them: a param becomes a
// uniform or constant of that name in GLSL, HLSL, WGSL and Godot's shading language alike, so a
// keyword or builtin of any of them would fail later, in one target, with an error that names
// generated code instead of the spec.
#pragma once

#include <string>

namespace crtforge::detail {

// The language that reserves `name` ("GLSL", "HLSL", "WGSL", "Godot"), or empty when none does.
std::string reserving_language(const std::string& name);

}  // namespace crtforge::detail
