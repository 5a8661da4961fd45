// Typed parameter values: the five param types an effect spec may declare.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <variant>

namespace crtforge {

enum class ParamType { Float, Int, Bool, Enum, Color };

const char* param_type_name(ParamType type);  // "float", "int", ...
bool parse_param_type(const std::string& text, ParamType& out);

using Color = std::array<double, 3>;  // linear RGB, each 0..1

// One param value. Enum values are stored by name.
using Value = std::variant<double, int64_t, bool, std::string, Color>;

// Round-trip text for keys and hashes: doubles shortest-exact, colours as three such numbers.
std::string value_to_exact_string(const Value& value);

// "#rrggbb" -> each channel / 255; false (and `out` untouched) for anything else.
bool parse_hex_color(const std::string& text, Color& out);

// Text for humans and JSON-free contexts: 0.3, 4, true, "shadow", #ff8000.
std::string value_to_string(const Value& value);

// A GLSL 450 constant expression for the value, exact enough to round-trip through float32.
// Enums are written as the index of the name in `enum_values` (callers pass it).
std::string value_to_glsl(const Value& value, ParamType type, int enum_index = -1);

// Shortest text that reads back as the same double, with a decimal point or exponent so GLSL (and
// Godot) parse it as a float literal: 0.3, 4.0, 1e-07.
std::string float_literal(double v);
// The same for a 32-bit float: the shortest text that reads back as that float ("0.3", not 0.30000001).
std::string float_literal(float v);

// The GLSL type used for a param of this type when it lives in the uniform block.
const char* glsl_type_for(ParamType type);

}  // namespace crtforge
