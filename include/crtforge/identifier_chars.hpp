// The characters of a GLSL identifier (ASCII letters, digits and '_'; a digit does not start one),
// tested without the C locale. Every scanner of shader text — the assembler, the importer, the
// compile-cache key, the emitters' word rewrites — asks the same question of the same bytes.
#pragma once

namespace crtforge::detail {

inline bool is_identifier_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
inline bool is_identifier_char(char c) { return is_identifier_start(c) || (c >= '0' && c <= '9'); }

}  // namespace crtforge::detail
