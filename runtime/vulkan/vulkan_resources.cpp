#include "runtime/vulkan/vulkan_resources.hpp"

#include <fmt/core.h>

#include "runtime/vulkan/job_validation.hpp"
#include "runtime/vulkan/vulkan_check.hpp"

namespace crtforge::vulkan {
namespace {

// The first memory type allowed by `type_bits` that has all of `required`; nullopt-like -1 if none.
int find_memory_type(const VkPhysicalDeviceMemoryProperties& memory, uint32_t type_bits,
                     VkMemoryPropertyFlags required) {
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & required) == required) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

Result<PooledMemory> allocate(const VulkanContext& context, const VkMemoryRequirements& needs, int type,
                              const char* what) {
    if (type < 0) return make_error(fmt::format("Vulkan device '{}' has no memory type for the {}", context.info().name, what));
    auto memory = context.memory_pool().take(static_cast<uint32_t>(type), needs.size);
    if (!memory) return make_error(fmt::format("{} for the {}", memory.error().message, what));
    return memory;
}

VkMappedMemoryRange whole_range(const HostBuffer& buffer) {
    VkMappedMemoryRange range{};
    range.sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE;
    range.memory = buffer.memory.get();
    range.offset = 0;
    range.size = VK_WHOLE_SIZE;  // whole mapping: sidesteps nonCoherentAtomSize alignment rules
    return range;
}

}  // namespace

Result<HostBuffer> create_host_buffer(const VulkanContext& context, VkDeviceSize size, VkBufferUsageFlags usage) {
    const VkDevice device = context.device();
    HostBuffer out;
    out.size = size;

    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (VkResult r = vkCreateBuffer(device, &info, nullptr, &buffer); r != VK_SUCCESS) return vk_error("vkCreateBuffer", r);
    out.buffer = UniqueBuffer(device, buffer);

    VkMemoryRequirements needs{};
    vkGetBufferMemoryRequirements(device, buffer, &needs);
    // Prefer coherent memory (no flush/invalidate); any host-visible type still works.
    int type = find_memory_type(context.memory_properties(), needs.memoryTypeBits,
                                VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (type < 0) {
        type = find_memory_type(context.memory_properties(), needs.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
        out.coherent = false;
    }
    auto memory = allocate(context, needs, type, "host-visible buffer");
    if (!memory) return memory.error();
    out.memory = std::move(memory).value();

    if (VkResult r = vkBindBufferMemory(device, buffer, out.memory.get(), 0); r != VK_SUCCESS) {
        return vk_error("vkBindBufferMemory", r);
    }
    auto mapped = out.memory.map();
    if (!mapped) return mapped.error();
    out.mapped = mapped.value();
    return out;
}

Status flush(const VulkanContext& context, const HostBuffer& buffer) {
    if (buffer.coherent) return Ok{};
    VkMappedMemoryRange range = whole_range(buffer);
    if (VkResult r = vkFlushMappedMemoryRanges(context.device(), 1, &range); r != VK_SUCCESS) {
        return vk_error("vkFlushMappedMemoryRanges", r);
    }
    return Ok{};
}

Status invalidate(const VulkanContext& context, const HostBuffer& buffer) {
    if (buffer.coherent) return Ok{};
    VkMappedMemoryRange range = whole_range(buffer);
    if (VkResult r = vkInvalidateMappedMemoryRanges(context.device(), 1, &range); r != VK_SUCCESS) {
        return vk_error("vkInvalidateMappedMemoryRanges", r);
    }
    return Ok{};
}

Result<DeviceImage> create_device_image(const VulkanContext& context, VkFormat format, uint32_t width,
                                        uint32_t height, VkImageUsageFlags usage, uint32_t levels) {
    const VkDevice device = context.device();
    DeviceImage out;
    out.format = format;
    out.extent = {width, height};
    out.levels = levels;

    VkImageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = levels;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    if (VkResult r = vkCreateImage(device, &info, nullptr, &image); r != VK_SUCCESS) return vk_error("vkCreateImage", r);
    out.image = UniqueImage(device, image);

    VkMemoryRequirements needs{};
    vkGetImageMemoryRequirements(device, image, &needs);
    // Device-local where the device has it; a CPU device like lavapipe may not flag any type so.
    int type = find_memory_type(context.memory_properties(), needs.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = find_memory_type(context.memory_properties(), needs.memoryTypeBits, 0);
    auto memory = allocate(context, needs, type, "image");
    if (!memory) return memory.error();
    out.memory = std::move(memory).value();
    if (VkResult r = vkBindImageMemory(device, image, out.memory.get(), 0); r != VK_SUCCESS) {
        return vk_error("vkBindImageMemory", r);
    }

    VkImageViewCreateInfo view{};
    view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1};
    VkImageView handle = VK_NULL_HANDLE;
    if (VkResult r = vkCreateImageView(device, &view, nullptr, &handle); r != VK_SUCCESS) {
        return vk_error("vkCreateImageView", r);
    }
    out.view = UniqueImageView(device, handle);
    return out;
}

Result<UniqueSampler> create_sampler(const VulkanContext& context, SamplerFilter filter, WrapMode wrap, bool mipmap,
                                     SamplerFilter mip_filter) {
    const VkFilter vk_filter = filter == SamplerFilter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    if (wrap == WrapMode::Repeat) address = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    if (wrap == WrapMode::MirroredRepeat) address = VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    if (wrap == WrapMode::ClampToBorder) address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;  // transparent black, below
    VkSamplerCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
    info.magFilter = vk_filter;
    info.minFilter = vk_filter;
    info.mipmapMode = mipmap && mip_filter == SamplerFilter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = address;
    info.addressModeV = address;
    info.addressModeW = address;
    info.minLod = 0.0f;
    info.maxLod = mipmap ? VK_LOD_CLAMP_NONE : 0.0f;  // without mipmaps level 0 only
    info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    VkSampler sampler = VK_NULL_HANDLE;
    if (VkResult r = vkCreateSampler(context.device(), &info, nullptr, &sampler); r != VK_SUCCESS) {
        return vk_error("vkCreateSampler", r);
    }
    return UniqueSampler(context.device(), sampler);
}

bool can_keep_target(const VulkanContext& context, OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba16Float:
        case OutputFormat::Rgba32Float:
        case OutputFormat::R16Float:
        case OutputFormat::Rg16Float: break;
        default: return false;
    }
    const VkFormatFeatureFlags target_needs = VK_FORMAT_FEATURE_BLIT_SRC_BIT;
    const VkFormatFeatureFlags texture_needs = VK_FORMAT_FEATURE_BLIT_DST_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                               VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT | VK_FORMAT_FEATURE_BLIT_SRC_BIT;
    return (context.optimal_tiling_features(output_vk_format(format)) & target_needs) == target_needs &&
           (context.optimal_tiling_features(VK_FORMAT_R32G32B32A32_SFLOAT) & texture_needs) == texture_needs;
}

Result<std::shared_ptr<UploadedImage>> create_uploaded_image(const VulkanContext& context, const Image& image,
                                                             VkFormat format, TextureTexels texels, bool mipmap) {
    auto out = std::make_shared<UploadedImage>();
    // A shader that samples nothing still gets a valid descriptor: a 1x1 transparent-black texture.
    const Image blank = Image::make(1, 1);
    const Image& source = image.empty() ? blank : image;
    if (image.device) {  // the job check has refused pictures another engine kept
        auto kept = std::dynamic_pointer_cast<const KeptTarget>(image.device);
        if (!kept || texels != TextureTexels::Rgba32Float || format != VK_FORMAT_R32G32B32A32_SFLOAT)
            return make_error("a picture kept on the device is sampled as RGBA32F only", {}, 0, "job.input");
        out->source = std::move(kept);
    } else {
        auto staging =
            create_host_buffer(context, source.pixel_count() * texel_bytes(texels), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        if (!staging) return staging.error();
        out->staging = std::move(staging).value();
        write_texels(source, texels, out->staging.mapped);
        if (auto s = flush(context, out->staging); !s) return s.error();
    }

    const uint32_t levels = mipmap ? mip_level_count(source.width, source.height) : 1;
    VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    if (levels > 1) usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // each level is blitted from the one above
    auto device_image = create_device_image(context, format, static_cast<uint32_t>(source.width),
                                            static_cast<uint32_t>(source.height), usage, levels);
    if (!device_image) return device_image.error();
    out->image = std::move(device_image).value();
    return out;
}

Result<SampledTexture> create_sampled_texture(const VulkanContext& context, std::shared_ptr<UploadedImage> texels,
                                              SamplerFilter filter, WrapMode wrap, SamplerFilter mip_filter, uint32_t binding) {
    SampledTexture out;
    out.binding = binding;
    out.texels = std::move(texels);
    auto sampler = create_sampler(context, filter, wrap, out.texels->image.levels > 1, mip_filter);
    if (!sampler) return sampler.error();
    out.sampler = std::move(sampler).value();
    return out;
}

}  // namespace crtforge::vulkan
