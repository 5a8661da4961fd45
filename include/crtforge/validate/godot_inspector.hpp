// What a Godot user sees in the inspector, held to the spec and the preset: each runtime param's
// uniform as the exported shader declares it (type, hint_range min/max/step, colour hint, default)
// and its value in the exported material (.tres). Read back from the files' text, independently
// of the writer, so a swapped range, a wrong step, an int's max, a colour's channels or alpha, or
// a default that is not the preset's fails validate.
#pragma once

#include <string>
#include <vector>

#include "crtforge/targets.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

// Each difference between the pass's Godot files (`out`: its shader and material, and the screen
// pair where there is one) and `variant`'s runtime params, one line each; empty when they agree.
// `godot_version` is 3 or 4.
std::vector<std::string> godot_inspector_problems(const Variant& variant, const TargetOutput& out, int godot_version);

}  // namespace crtforge
