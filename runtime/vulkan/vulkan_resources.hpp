// Buffers, images and their memory for one job. Everything is owned by RAII members, so a job's
// objects disappear when its render() returns, whichever way it returns.
#pragma once

#include <memory>

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/render_engine.hpp"
#include "runtime/common/pixel_conversion.hpp"
#include "runtime/vulkan/vulkan_context.hpp"
#include "runtime/vulkan/vulkan_handle.hpp"

namespace crtforge::vulkan {

// A buffer in host-visible memory, mapped for its whole life (its memory stays mapped in the pool).
// Members are declared so the buffer is destroyed before the memory it is bound to.
struct HostBuffer {
    PooledMemory memory;
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

// A single-layer 2D image in device-local memory (optimal tiling) with a colour view of all its
// `levels` mip levels (level 0 is extent).
struct DeviceImage {
    PooledMemory memory;  // declared first: released after the view and the image
    UniqueImage image;
    UniqueImageView view;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    uint32_t levels = 1;
};

Result<DeviceImage> create_device_image(const VulkanContext& context, VkFormat format, uint32_t width,
                                        uint32_t height, VkImageUsageFlags usage, uint32_t levels = 1);

// `wrap` on every axis, unnormalised coordinates off, no anisotropy. Without `mipmap` only level
// 0 is read; with it every level, blended as `mip_filter` says.
Result<UniqueSampler> create_sampler(const VulkanContext& context, SamplerFilter filter, WrapMode wrap, bool mipmap,
                                     SamplerFilter mip_filter);

// A pass's target kept on the device (RenderJob::keep_on_device), in TRANSFER_SRC_OPTIMAL as its
// render pass left it: its readers' textures are blitted from it. It keeps the context (device and
// memory pool) alive, so it may outlive the engine; it must be released on the engine's thread.
struct KeptTarget final : DevicePicture {
    std::shared_ptr<const VulkanContext> context;  // declared first: goes after the image
    DeviceImage image;
    const void* owner() const override { return context.get(); }
};

// Whether a target of `format` can be kept on `context`'s device: a float format its readers'
// RGBA32F textures take by a blit, exactly (every half and float is a float), where the device can
// blit it into, sample and filter RGBA32F. 8-bit targets are read back: the device's conversion of
// a byte to float is not always the read-back's byte / 255 to the last bit.
bool can_keep_target(const VulkanContext& context, OutputFormat format);

// A texture's texels on the device. `staging` holds them on their way up, or `source` where they
// come from a kept target, until the first command buffer that uploads them has run
// (mark_uploaded() then releases it); after that the image is in SHADER_READ_ONLY_OPTIMAL and any
// later job may sample it as it is.
struct UploadedImage {
    HostBuffer staging;
    std::shared_ptr<const KeptTarget> source;
    DeviceImage image;
    bool uploaded = false;

    void mark_uploaded() {
        uploaded = true;
        staging = HostBuffer{};
        source.reset();
    }
};

// `image` (empty = a 1x1 transparent-black texture) written as `texels` into a staging buffer,
// and a `format` image of its size to receive it: with `mipmap`, with a full mip chain that the
// upload fills (RenderJob::mipmap). A picture kept on this device is blitted from its target
// instead (RGBA32F texels only: what can_keep_target promises).
Result<std::shared_ptr<UploadedImage>> create_uploaded_image(const VulkanContext& context, const Image& image,
                                                             VkFormat format, TextureTexels texels, bool mipmap);

// One texture a pass samples: its texels (shared with the engine's upload cache, so a LUT that
// every pass and frame reads goes up once) and its sampler.
struct SampledTexture {
    std::shared_ptr<UploadedImage> texels;
    UniqueSampler sampler;
    uint32_t binding = 0;  // of its combined image sampler in the job's set
};

// Samples every level of `texels` when it has more than one, blended as `mip_filter` says.
Result<SampledTexture> create_sampled_texture(const VulkanContext& context, std::shared_ptr<UploadedImage> texels,
                                              SamplerFilter filter, WrapMode wrap, SamplerFilter mip_filter, uint32_t binding);

}  // namespace crtforge::vulkan
