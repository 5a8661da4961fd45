// What Godot 3's shading-language parser needs beyond Godot 4's: text rewrites of a canvas_item
// shader SPIRV-Cross printed (each keeps the meaning; each was found by a shader Godot 3 refused).
#pragma once

#include <string>

namespace crtforge::godot::godot3 {

// Every rewrite below, in the order they must run. Throws spirv_cross::CompilerError for a
// construct Godot 3 cannot be given (the message names it).
std::string with_godot3_syntax(const std::string& text);

// Global `const T name[N] = T[](...);` arrays (Godot 3: "Expected initialization of constant")
// become the same array declared at the top of each function that reads it.
std::string with_constant_arrays_local(const std::string& text);
// `a = b;` of two arrays ("Expected '[' or '.'": Godot 3 assigns arrays only element by element)
// becomes a loop over their elements; `a = float[](x, y);` an assignment of each argument.
std::string with_array_copies_elementwise(const std::string& text);
// A for loop declaring several variables (`for (float a = x, b = y; ...)`, printed to GLSL without
// its commas) declares all but the first before it.
std::string with_loop_declarations_single(const std::string& text);
// A for loop whose steps are a comma list (`i++, j = k`: "Expected ')' after third expression")
// takes its steps at the end of its body; a body that continues cannot, and is refused.
std::string with_loop_steps_in_body(const std::string& text);
// A for loop without a step, or without a condition, gets a step that changes nothing and `true`.
std::string with_loop_increments(const std::string& text);
// A for loop with no initialiser (`for (; i < 6; i++)`: "Expected expression, found: PERIOD") gets
// the declaration of an int nothing reads.
std::string with_loop_initialisers(const std::string& text);
// A float literal Godot 3 would print with fewer digits than its float needs (six: %g) as
// uintBitsToFloat(uint(<its bits as an int>)).
std::string with_float_literals_exact(const std::string& text);
// 4u as uint(4): Godot 3 reads the literal as an int.
std::string with_unsigned_literals_spelled(const std::string& text);
// `a - (-b)` as `a + b` for a name or a number b: Godot 3 prints it to GLSL as `(a--b)`, which the
// GL driver reads as a decrement ("unexpected FLOATCONSTANT": tvout-tweaks).
std::string with_negated_subtrahends_added(const std::string& text);

}  // namespace crtforge::godot::godot3
