// Validate's output for GitHub Actions: workflow-command annotations and the step summary.
#pragma once

#include <functional>
#include <string>

#include "crtforge/validate/validation.hpp"

namespace crtforge::cli {

bool running_on_github_actions();

// Nothing unless GITHUB_ACTIONS=true. `preset_file` says where a preset is written (for checks whose
// message names no file); it may be empty (report merge has no templates).
void annotate_for_github(const ValidationReport& report, const std::function<SourceLocation(const std::string& preset)>& preset_file);

}  // namespace crtforge::cli
