// Static checks on stage snippets before anything compiles: constructs whose result the shading
// languages leave undefined, or that one target rejects, found in the text with the snippet's
// file and line (docs/hard-cases.md lists what each target would do instead).
#pragma once

#include <string>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spec.hpp"

namespace crtforge::detail {

// The first of, in `stage.glsl_source` (comments ignored):
//   smoothstep(a, b, x) with constant edges a >= b   undefined in GLSL and HLSL, a WGSL error
//   pow(c, y) with a constant base c < 0             undefined (NaN on most GPUs)
//   a division by a literal zero
//   a division by a float param whose range includes 0 (0 is a value the preset may set)
// Each is an Input error at the snippet's file:line, field "glsl".
Status lint_stage_source(const StageSpec& stage);

// GLSL text with its // and /* */ comments blanked (newlines kept, so lines still count).
std::string without_comments(const std::string& text);

}  // namespace crtforge::detail
