// The params both Godot runners set on a material (tools/godot3-runner, tools/godot4-runner), as
// JSON: uniform name -> number, bool or [r, g, b]; each runner converts a value by the uniform's
// declared type. Shared by the Godot 3 and Godot 4 engines.
#pragma once

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "crtforge/diagnostic.hpp"
#include "crtforge/value.hpp"

namespace crtforge::detail {

// Keys in name order. A non-finite number or colour channel and an enum name (pass the enum's
// index) are Input errors on the field "job.params".
Result<nlohmann::json> godot_params_json(const std::map<std::string, Value>& params);

}  // namespace crtforge::detail
