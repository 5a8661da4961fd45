// Checks a RenderJob against the device's limits and against what its SPIR-V declares, before any
// GPU work: drivers need not survive a bad job, and the validation layer is not always on, so
// every job the engine accepts is one the Vulkan spec says is valid to run.
#pragma once

#include <vector>

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "runtime/common/pixel_conversion.hpp"
#include "runtime/vulkan/vulkan_context.hpp"

namespace crtforge::vulkan {

// How one sampled texture is uploaded.
struct TexturePlan {
    VkFormat format = VK_FORMAT_UNDEFINED;
    TextureTexels texels = TextureTexels::Rgba32Float;
};

// What an accepted job will use.
struct JobPlan {
    VkFormat output_format = VK_FORMAT_UNDEFINED;
    std::vector<TexturePlan> textures;  // [0] the input, then job.textures in order
};

VkFormat output_vk_format(OutputFormat format);

Result<JobPlan> check_job(const VulkanContext& context, const RenderJob& job);

}  // namespace crtforge::vulkan
