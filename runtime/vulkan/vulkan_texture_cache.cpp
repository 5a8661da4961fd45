#include "runtime/vulkan/vulkan_texture_cache.hpp"

#include <memory>

namespace crtforge::vulkan {

Result<std::shared_ptr<UploadedImage>> TextureCache::get(const VulkanContext& context, const SharedImage& image,
                                                         VkFormat format, TextureTexels texels, bool mipmap) {
    if (!image.identity()) return create_uploaded_image(context, *image, format, texels, mipmap);
    const std::shared_ptr<const Image>& identity = image.identity();
    for (auto it = entries_.begin(); it != entries_.end();) {
        if (it->image.expired()) {  // its picture is gone: nothing can ask for it again
            bytes_ -= it->bytes;
            it = entries_.erase(it);
            continue;
        }
        const bool same = !it->image.owner_before(identity) && !identity.owner_before(it->image);
        if (!same || it->format != format || it->texels != texels || it->mipmap != mipmap) {
            ++it;
            continue;
        }
        entries_.splice(entries_.begin(), entries_, it);
        return entries_.front().uploaded;
    }
    auto uploaded = create_uploaded_image(context, *image, format, texels, mipmap);
    if (!uploaded) return uploaded.error();
    // A picture near the image budget is not kept: it would hold its memory, twice, past its job.
    const VkDeviceSize level0 = VkDeviceSize{image->pixel_count()} * texel_bytes(texels);
    const VkDeviceSize bytes = mipmap ? level0 + level0 / 3 : level0;  // a chain adds about a third
    if (bytes > budget_ / 4) return uploaded;
    entries_.push_front({image.identity(), format, texels, mipmap, uploaded.value(), bytes});
    bytes_ += bytes;
    while (bytes_ > budget_) {
        bytes_ -= entries_.back().bytes;
        entries_.pop_back();
    }
    return uploaded;
}

}  // namespace crtforge::vulkan
