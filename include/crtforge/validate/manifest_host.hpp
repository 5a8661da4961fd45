// The host an engine integrator writes: it knows each pass's uniform block (binding, size, every
// member's name, type, offset) and textures (name, binding) only from manifest.json. validate's
// Vulkan renders go through this view of the passes, so a wrong offset, binding or block size in
// the shipped manifest draws a wrong picture and fails, instead of hiding behind SPIR-V reflection.
#pragma once

#include <vector>

#include "crtforge/exporter.hpp"

namespace crtforge {

// `passes` with each reflection replaced by what the preset's manifest entry (the one export
// writes) says of the pass; an error when the entry lacks or garbles what a host needs.
Result<std::vector<CompiledVariant>> as_manifest_host(const Preset& preset, const std::vector<CompiledVariant>& passes);

}  // namespace crtforge
