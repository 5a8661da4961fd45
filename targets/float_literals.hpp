// SPIRV-Cross prints a float constant as the exact decimal of its float32 value
// (0.300000011920928955078125): correct, but not what anyone wrote or wants to hand-tune.
#pragma once

#include <functional>
#include <string>

namespace crtforge::detail {

// `source` with every float literal that is exactly a float32 value rewritten as the shortest
// decimal that reads back as the same float32 (0.3, 3.14159), keeping any suffix (HLSL's `f`).
// Comments, identifiers, integers, doubles (a value no float32 has) and literals whose shortest
// form would need an exponent are left as they are, so the program means exactly what it meant.
std::string shorten_float_literals(const std::string& source);

// `source` with each float literal outside comments and preprocessor lines (digits with a '.' or an
// exponent, and the identifier characters that follow it: a suffix such as `f`) replaced by
// `rewrite(token, suffix)`, which returns the whole replacement, suffix included.
std::string rewrite_float_literals(const std::string& source,
                                   const std::function<std::string(const std::string& token, const std::string& suffix)>& rewrite);

// `source` with a component of a constant splat written as the constant: SPIRV-Cross prints a
// select of a constant vector component by component as `c.x ? vec4(0.0).x : v.x` (GLSL, Godot)
// or `0.0f.xxxx.x` (HLSL); these read `0.0` (a negative one `(-1.0)`). Comments and preprocessor
// lines are left as they are.
std::string without_splat_selects(const std::string& source);

}  // namespace crtforge::detail
