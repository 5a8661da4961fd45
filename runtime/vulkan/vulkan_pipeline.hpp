// The graphics pipeline for one full-screen pass and the descriptor set that feeds it.
#pragma once

#include <list>
#include <memory>
#include <string>

#include <vector>

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "runtime/vulkan/vulkan_context.hpp"
#include "runtime/vulkan/vulkan_handle.hpp"
#include "runtime/vulkan/vulkan_resources.hpp"

namespace crtforge::vulkan {

// Members are declared in creation order, so they are destroyed pipeline-first.
struct GraphicsPass {
    UniqueRenderPass render_pass;
    UniqueDescriptorSetLayout empty_set_layout;  // fills sets below job.descriptor_set
    UniqueDescriptorSetLayout set_layout;        // the job's uniform buffer + combined image samplers
    UniquePipelineLayout pipeline_layout;
    UniquePipeline pipeline;
};

// One colour attachment of `color_format`, cleared (to the job's clear colour, when the pass
// begins) and left in TRANSFER_SRC_OPTIMAL for the readback copy; viewport and scissor fixed to
// the job's viewport (its whole size by default).
Result<GraphicsPass> create_graphics_pass(const VulkanContext& context, const RenderJob& job, VkFormat color_format);

// The graphics passes an engine has built, by everything create_graphics_pass reads from the job
// (the two modules, the descriptor layout, the viewport, clip_y_up) and the colour format: a pass
// drawn every frame, and a pass that several presets share, is compiled by the driver once.
// At most `capacity` passes, least recently used first out; a job holds what it uses.
class GraphicsPassCache {
public:
    explicit GraphicsPassCache(size_t capacity) : capacity_(capacity) {}
    Result<std::shared_ptr<const GraphicsPass>> get(const VulkanContext& context, const RenderJob& job, VkFormat color_format);

private:
    struct Entry {
        size_t hash;
        std::string key;
        std::shared_ptr<const GraphicsPass> pass;
    };
    const size_t capacity_;
    std::list<Entry> entries_;  // most recently used first
};

Result<UniqueFramebuffer> create_framebuffer(const VulkanContext& context, VkRenderPass render_pass,
                                             const DeviceImage& target);

struct DescriptorSet {
    UniqueDescriptorPool pool;  // owns `set`
    VkDescriptorSet set = VK_NULL_HANDLE;
};

// Writes the job's bindings: `uniforms` (null when the job has no uniform data) and every texture
// at its binding.
Result<DescriptorSet> create_descriptor_set(const VulkanContext& context, const GraphicsPass& pass,
                                            const RenderJob& job, const HostBuffer* uniforms,
                                            const std::vector<SampledTexture>& textures);

}  // namespace crtforge::vulkan
