// The textures an engine has uploaded, by the identity of the SharedImage they came from: a
// scene's LUTs (a bezel pack's are hundreds of MB as floats) and the outputs a pass shares with
// several readers go to the device once, not once per pass and frame. An entry refers to its
// image weakly: it does not keep the picture alive (holding them, four times the bytes of their
// 8-bit device copies, took a corpus sweep's two engines past 10 GB), and an entry whose picture
// is gone can never be asked for again, so it goes. A weak reference keeps its control block,
// so no new image can take the identity while the entry lives. Bounded in device bytes, least
// recently used first out, and no texture over a quarter of the bound is kept; a job keeps what it
// uses alive until it is done.
#pragma once

#include <list>
#include <memory>

#include "crtforge/runtime/image.hpp"
#include "runtime/vulkan/vulkan_resources.hpp"

namespace crtforge::vulkan {

class TextureCache {
public:
    explicit TextureCache(VkDeviceSize budget_bytes) : budget_(budget_bytes) {}

    // `image`'s texels as `format` / `texels`: the ones already on the device, or new ones that the
    // next command buffer sampling them uploads. An image without identity (empty) is not kept.
    Result<std::shared_ptr<UploadedImage>> get(const VulkanContext& context, const SharedImage& image, VkFormat format,
                                               TextureTexels texels, bool mipmap);

private:
    struct Entry {
        std::weak_ptr<const Image> image;
        VkFormat format;
        TextureTexels texels;
        bool mipmap;
        std::shared_ptr<UploadedImage> uploaded;
        VkDeviceSize bytes;
    };
    const VkDeviceSize budget_;
    VkDeviceSize bytes_ = 0;
    std::list<Entry> entries_;  // most recently used first
};

}  // namespace crtforge::vulkan
