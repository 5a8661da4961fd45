// Recording and running the command buffer of one job:
//   upload the textures -> clear the target, render the full-screen triangle -> copy the target to a
//   host-visible buffer, each step ordered after the previous one by a barrier.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"
#include "runtime/vulkan/vulkan_context.hpp"
#include "runtime/vulkan/vulkan_pipeline.hpp"
#include "runtime/vulkan/vulkan_resources.hpp"

namespace crtforge::vulkan {

struct PassCommands {
    const std::vector<SampledTexture>& textures;  // each not yet on the device receives its staging, then is sampled
    const GraphicsPass& pass;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkDescriptorSet descriptor_set = VK_NULL_HANDLE;
    uint32_t descriptor_set_index = 0;
    const DeviceImage& target;       // the colour attachment
    const HostBuffer& readback;      // receives `target`, tightly packed; no buffer: the target is kept
    std::array<float, 4> clear_color{};  // the whole target's value before the draw
};

void record_pass(VkCommandBuffer commands, const PassCommands& pass);

// The textures' uploads alone: a job timed many times uploads once (time_draws()).
void record_uploads(VkCommandBuffer commands, const PassCommands& pass);

// One untimed draw, then `draws` draws between two timestamps (query 0 and 1 of `queries`), no
// readback: one timing of time_draws(). The textures must have been uploaded.
void record_timed_draws(VkCommandBuffer commands, const PassCommands& pass, VkQueryPool queries, int draws);

// Records with `record` into a fresh one-time command buffer, submits it to the context's queue
// and blocks until the device has finished it.
Status submit_and_wait(const VulkanContext& context, const std::function<void(VkCommandBuffer)>& record);

}  // namespace crtforge::vulkan
