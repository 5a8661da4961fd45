// SPIR-V target: the optimised, validated modules as binary files (for Vulkan hosts).
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::spirv {

struct Options {};  // the modules are written as compiled; nothing to choose

Result<TargetOutput> generate(const TargetInput& input, const Options& options = {});

// The spirv target's record (crtforge/targets.hpp).
std::vector<TargetInfo> records();

}  // namespace crtforge::spirv
