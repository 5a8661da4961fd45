#include "runtime/vulkan/vulkan_commands.hpp"

#include <algorithm>
#include <cstdint>

#include "crtforge/runtime/gpu_watchdog.hpp"
#include "runtime/vulkan/vulkan_check.hpp"
#include "runtime/vulkan/vulkan_handle.hpp"

namespace crtforge::vulkan {
namespace {

constexpr VkImageSubresourceRange kColorRange{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
constexpr VkImageSubresourceLayers kColorLayers{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};

// `levels` mip levels from `first` (default: the one level of a target).
void image_barrier(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to,
                   VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
                   VkPipelineStageFlags dst_stage, uint32_t first = 0, uint32_t levels = 1) {
    VkImageMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    barrier.srcAccessMask = src_access;
    barrier.dstAccessMask = dst_access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = kColorRange;
    barrier.subresourceRange.baseMipLevel = first;
    barrier.subresourceRange.levelCount = levels;
    vkCmdPipelineBarrier(commands, src_stage, dst_stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

// Tightly packed copy region covering a whole single-layer image.
VkBufferImageCopy whole_image(const DeviceImage& image) {
    VkBufferImageCopy region{};
    region.bufferOffset = 0;
    region.bufferRowLength = 0;    // 0 = rows are packed: width texels apart
    region.bufferImageHeight = 0;
    region.imageSubresource = kColorLayers;
    region.imageOffset = {0, 0, 0};
    region.imageExtent = {image.extent.width, image.extent.height, 1};
    return region;
}

// Level i of a mip chain from level i - 1, as RetroArch fills its chains: a linear blit of the
// whole level onto the next one's size (halved, rounded down, at least 1). Level i - 1 ends in
// TRANSFER_SRC_OPTIMAL, level i stays in TRANSFER_DST_OPTIMAL.
void record_mip_level(VkCommandBuffer commands, const DeviceImage& texture, uint32_t level) {
    auto extent = [&](uint32_t l) {
        return VkOffset3D{static_cast<int32_t>(std::max(texture.extent.width >> l, 1u)),
                          static_cast<int32_t>(std::max(texture.extent.height >> l, 1u)), 1};
    };
    image_barrier(commands, texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, level - 1, 1);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
    blit.srcOffsets[1] = extent(level - 1);
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
    blit.dstOffsets[1] = extent(level);
    vkCmdBlitImage(commands, texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, texture.image.get(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
}

// Texels already on the device (an earlier job uploaded them) record nothing.
void record_upload(VkCommandBuffer commands, const UploadedImage& texels) {
    if (texels.uploaded) return;
    const HostBuffer& staging = texels.staging;
    const DeviceImage& texture = texels.image;
    const uint32_t levels = texture.levels;
    image_barrier(commands, texture.image.get(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                  VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, levels);
    if (texels.source) {
        // A kept target, converted to the texture's format by a blit of the same size (nearest: each
        // texel onto itself). It stays in TRANSFER_SRC_OPTIMAL for its other readers.
        const DeviceImage& target = texels.source->image;
        image_barrier(commands, target.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkImageBlit blit{};
        blit.srcSubresource = kColorLayers;
        blit.srcOffsets[1] = {static_cast<int32_t>(target.extent.width), static_cast<int32_t>(target.extent.height), 1};
        blit.dstSubresource = kColorLayers;
        blit.dstOffsets[1] = {static_cast<int32_t>(texture.extent.width), static_cast<int32_t>(texture.extent.height), 1};
        vkCmdBlitImage(commands, target.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, texture.image.get(),
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    } else {
        const VkBufferImageCopy region = whole_image(texture);
        vkCmdCopyBufferToImage(commands, staging.buffer.get(), texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &region);
    }
    for (uint32_t level = 1; level < levels; ++level) record_mip_level(commands, texture, level);
    // Sampled from both stages' point of view: the vertex shader could sample too. Every level but
    // the last was a blit's source.
    const VkPipelineStageFlags shaders = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    if (levels > 1)
        image_barrier(commands, texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT, VK_ACCESS_SHADER_READ_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, shaders, 0, levels - 1);
    image_barrier(commands, texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, shaders, levels - 1, 1);
}

void record_draw(VkCommandBuffer commands, const PassCommands& c) {
    VkClearValue clear{};
    clear.color = {{c.clear_color[0], c.clear_color[1], c.clear_color[2], c.clear_color[3]}};
    VkRenderPassBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.renderPass = c.pass.render_pass.get();
    begin.framebuffer = c.framebuffer;
    begin.renderArea = {{0, 0}, c.target.extent};
    begin.clearValueCount = 1;
    begin.pClearValues = &clear;
    vkCmdBeginRenderPass(commands, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, c.pass.pipeline.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, c.pass.pipeline_layout.get(),
                            c.descriptor_set_index, 1, &c.descriptor_set, 0, nullptr);
    vkCmdDraw(commands, 3, 1, 0, 0);  // one triangle covering the viewport, positions from gl_VertexIndex
    vkCmdEndRenderPass(commands);     // leaves the target in TRANSFER_SRC_OPTIMAL
}

void record_readback(VkCommandBuffer commands, const DeviceImage& target, const HostBuffer& readback) {
    const VkBufferImageCopy region = whole_image(target);
    vkCmdCopyImageToBuffer(commands, target.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           readback.buffer.get(), 1, &region);
    // Make the copy visible to the host's reads after the fence.
    VkBufferMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.buffer = readback.buffer.get();
    barrier.offset = 0;
    barrier.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1,
                         &barrier, 0, nullptr);
}

}  // namespace

void record_pass(VkCommandBuffer commands, const PassCommands& pass) {
    for (const SampledTexture& texture : pass.textures) record_upload(commands, *texture.texels);
    record_draw(commands, pass);
    if (pass.readback.buffer.get() != VK_NULL_HANDLE) record_readback(commands, pass.target, pass.readback);  // none: kept
}

void record_uploads(VkCommandBuffer commands, const PassCommands& pass) {
    for (const SampledTexture& texture : pass.textures) record_upload(commands, *texture.texels);
}

void record_timed_draws(VkCommandBuffer commands, const PassCommands& pass, VkQueryPool queries, int draws) {
    record_draw(commands, pass);  // warm-up: the caches hold this pass's pipeline and textures again
    vkCmdResetQueryPool(commands, queries, 0, 2);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries, 0);
    for (int i = 0; i < draws; ++i) record_draw(commands, pass);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries, 1);
}

Status submit_and_wait(const VulkanContext& context, const std::function<void(VkCommandBuffer)>& record) {
    const VkDevice device = context.device();

    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool_info.queueFamilyIndex = context.queue_family();
    VkCommandPool pool_handle = VK_NULL_HANDLE;
    if (VkResult r = vkCreateCommandPool(device, &pool_info, nullptr, &pool_handle); r != VK_SUCCESS) {
        return vk_error("vkCreateCommandPool", r);
    }
    UniqueCommandPool pool(device, pool_handle);  // frees the command buffer with it

    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = pool.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    if (VkResult r = vkAllocateCommandBuffers(device, &alloc, &commands); r != VK_SUCCESS) {
        return vk_error("vkAllocateCommandBuffers", r);
    }

    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    if (VkResult r = vkBeginCommandBuffer(commands, &begin); r != VK_SUCCESS) return vk_error("vkBeginCommandBuffer", r);
    record(commands);
    if (VkResult r = vkEndCommandBuffer(commands); r != VK_SUCCESS) return vk_error("vkEndCommandBuffer", r);

    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VkFence fence_handle = VK_NULL_HANDLE;
    if (VkResult r = vkCreateFence(device, &fence_info, nullptr, &fence_handle); r != VK_SUCCESS) {
        return vk_error("vkCreateFence", r);
    }
    UniqueFence fence(device, fence_handle);

    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    if (VkResult r = vkQueueSubmit(context.queue(), 1, &submit, fence.get()); r != VK_SUCCESS) {
        return vk_error("vkQueueSubmit", r);
    }
    // Never returns early (that would free objects the device may still be using): a draw past
    // --gpu-timeout stops the process instead (GpuWait).
    GpuWait wait;
    for (;;) {
        const VkResult r = vkWaitForFences(device, 1, &fence_handle, VK_TRUE, kGpuWaitSliceNs);
        if (r == VK_SUCCESS) return Ok{};
        if (r != VK_TIMEOUT) return vk_error("vkWaitForFences", r);
        wait.still_waiting();
    }
}

}  // namespace crtforge::vulkan
