// Just enough SPIR-V reading to check a job before handing it to a driver: the entry points and
// the resources (descriptor bindings, uniform block sizes, push constants, vertex inputs) a module
// declares. Drivers are not required to survive invalid input, and without the validation layer
// nothing else would check these, so the engine refuses such jobs with a clear error instead.
// It is not a validator: the generator runs spirv-val on everything it emits.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "crtforge/diagnostic.hpp"

namespace crtforge::vulkan {

// SPIR-V execution models the engine cares about (values from the SPIR-V specification).
enum class ExecutionModel : uint32_t { Vertex = 0, Fragment = 4 };

struct SpirvEntryPoint {
    uint32_t execution_model = 0;
    std::string name;
};

enum class SpirvResourceKind { UniformBuffer, CombinedImageSampler, SampledImage, Sampler, StorageBuffer,
                               StorageImage, Other };
const char* resource_kind_name(SpirvResourceKind kind);

struct SpirvResource {
    std::string name;  // OpName of the variable (or of its block type), may be empty
    uint32_t set = 0, binding = 0;
    SpirvResourceKind kind = SpirvResourceKind::Other;
    uint32_t array_size = 1;  // > 1 for arrays of descriptors
    uint64_t block_bytes = 0; // UniformBuffer: bytes from the block start to the end of its last member
};

struct SpirvInterface {
    std::vector<SpirvEntryPoint> entry_points;
    std::vector<SpirvResource> resources;  // every descriptor-backed variable in the module
    bool push_constants = false;
    bool user_inputs = false;              // Input variables that are not built-ins (in a vertex
                                           // shader: vertex attributes, which the engine never feeds)
};

// `what` names the module in errors ("vertex shader"). Fails on a malformed word stream.
Result<SpirvInterface> inspect_spirv(std::span<const uint32_t> words, std::string_view what);

bool has_entry_point(const SpirvInterface& module, ExecutionModel model, std::string_view name);

}  // namespace crtforge::vulkan
