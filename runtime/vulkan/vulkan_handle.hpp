// Move-only owners for Vulkan objects that belong to a VkDevice, so every per-job object is
// destroyed on every path out of render() — early error returns included — in reverse order of
// creation (members and locals unwind last-created first).
#pragma once

#include <utility>

#include <vulkan/vulkan.h>

namespace crtforge::vulkan {

// `Destroy` is the matching vkDestroy*/vkFree* entry point; all share the shape
// (VkDevice, Handle, const VkAllocationCallbacks*).
template <typename Handle, auto Destroy>
class DeviceObject {
public:
    DeviceObject() = default;
    DeviceObject(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
    ~DeviceObject() { reset(); }

    DeviceObject(DeviceObject&& other) noexcept
        : device_(other.device_), handle_(std::exchange(other.handle_, Handle{})) {}
    DeviceObject& operator=(DeviceObject&& other) noexcept {
        if (this != &other) {
            reset();
            device_ = other.device_;
            handle_ = std::exchange(other.handle_, Handle{});
        }
        return *this;
    }
    DeviceObject(const DeviceObject&) = delete;
    DeviceObject& operator=(const DeviceObject&) = delete;

    Handle get() const { return handle_; }
    explicit operator bool() const { return handle_ != Handle{}; }

    void reset() {
        if (handle_ != Handle{}) Destroy(device_, handle_, nullptr);
        handle_ = Handle{};
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    Handle handle_{};
};

using UniqueBuffer = DeviceObject<VkBuffer, &vkDestroyBuffer>;
using UniqueImage = DeviceObject<VkImage, &vkDestroyImage>;
using UniqueImageView = DeviceObject<VkImageView, &vkDestroyImageView>;
using UniqueSampler = DeviceObject<VkSampler, &vkDestroySampler>;
using UniqueShaderModule = DeviceObject<VkShaderModule, &vkDestroyShaderModule>;
using UniqueDescriptorSetLayout = DeviceObject<VkDescriptorSetLayout, &vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = DeviceObject<VkDescriptorPool, &vkDestroyDescriptorPool>;  // frees its sets
using UniquePipelineLayout = DeviceObject<VkPipelineLayout, &vkDestroyPipelineLayout>;
using UniqueRenderPass = DeviceObject<VkRenderPass, &vkDestroyRenderPass>;
using UniquePipeline = DeviceObject<VkPipeline, &vkDestroyPipeline>;
using UniqueFramebuffer = DeviceObject<VkFramebuffer, &vkDestroyFramebuffer>;
using UniqueCommandPool = DeviceObject<VkCommandPool, &vkDestroyCommandPool>;  // frees its buffers
using UniqueFence = DeviceObject<VkFence, &vkDestroyFence>;

}  // namespace crtforge::vulkan
