// Buffers, images and their memory for one job. Everything is owned by RAII members, so a job's
// objects disappear when its render() returns, whichever way it returns.
#pragma once

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "runtime/common/pixel_conversion.hpp"
#include "runtime/vulkan/vulkan_context.hpp"
#include "runtime/vulkan/vulkan_handle.hpp"

namespace crtforge::vulkan {

// A buffer in host-visible memory, mapped for its whole life (freeing the memory unmaps it).
// Members are declared so the buffer is destroyed before the memory it is bound to.
struct HostBuffer {
    UniqueMemory memory;
    UniqueBuffer buffer;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
    bool coherent = true;  // false: writes need flush(), reads need invalidate()
};

// `size` must be > 0.
Result<HostBuffer> create_host_buffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage);
// Make host writes visible to the device / device writes visible to the host (no-ops when coherent).
Status flush(const VulkanContext& context, const HostBuffer& buffer);
Status invalidate(const VulkanContext& context, const HostBuffer& buffer);

// A single-mip, single-layer 2D image in device-local memory (optimal tiling) with a colour view.
struct DeviceImage {
    UniqueMemory memory;  // declared first: released after the view and the image
    UniqueImage image;
    UniqueImageView view;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
};

Result<DeviceImage> create_device_image(const VulkanContext& context, VkFormat format, uint32_t width,
                                        uint32_t height, VkImageUsageFlags usage);

// `wrap` on every axis, unnormalised coordinates off, no mipmaps, no anisotropy.
Result<UniqueSampler> create_sampler(const VulkanContext& context, SamplerFilter filter, WrapMode wrap);

// One texture a pass samples: its texels on their way up, the image they go to, its sampler.
// Members are declared so the sampler and image go before the staging buffer.
struct SampledTexture {
    HostBuffer staging;  // tightly packed texels, copied into `image` by the command buffer
    DeviceImage image;
    UniqueSampler sampler;
    uint32_t binding = 0;  // of its combined image sampler in the job's set
};

// The one upload path of the input and of every extra texture: `image` (empty = a 1x1
// transparent-black texture) written as `texels` into a staging buffer, a `format` image of its
// size to receive it, and a sampler with `filter` and `wrap`.
Result<SampledTexture> create_sampled_texture(const VulkanContext& context, const Image& image, VkFormat format,
                                              TextureTexels texels, SamplerFilter filter, WrapMode wrap,
                                              uint32_t binding);

}  // namespace crtforge::vulkan
