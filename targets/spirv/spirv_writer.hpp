// SPIR-V target: the optimised, validated modules as binary files (for Vulkan hosts).
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::spirv {

struct Options {};  // the modules are written as compiled; nothing to choose

Result<TargetOutput> Generate(const TargetInput& input, const Options& options = {});

}  // namespace crtforge::spirv
