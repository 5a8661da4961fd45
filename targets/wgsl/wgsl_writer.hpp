// The wgsl target: one WGSL module per preset with both entry points (vs_main, fs_main) for
// WebGPU hosts, written by crtforge's own emitter (targets/wgsl/wgsl_emitter.hpp), plus the
// bind-group layout and uniform-buffer byte layout in the manifest.
#pragma once

#include "crtforge/targets.hpp"

namespace crtforge::wgsl {

inline constexpr const char* kVertexEntry = "vs_main";
inline constexpr const char* kFragmentEntry = "fs_main";

Result<TargetOutput> generate(const TargetInput& input);

// The wgsl record (crtforge/targets.hpp).
std::vector<TargetInfo> records();

}  // namespace crtforge::wgsl
