// The long-lived Vulkan objects an engine reuses across jobs: the instance (with the validation
// layer's debug messenger when asked for) and one logical device with one graphics queue.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"
#include "runtime/vulkan/vulkan_memory_pool.hpp"
#include "crtforge/runtime/render_engine.hpp"

namespace crtforge::vulkan {

// Warning- and error-severity messages from the validation layer. The layer may call back from a
// driver thread, hence the lock.
class ValidationLog {
public:
    void add(std::string message);
    std::vector<std::string> take();  // returns and clears what was collected

private:
    std::mutex mutex_;
    std::vector<std::string> messages_;
};

class VulkanInstance {
public:
    // `validation` enables VK_LAYER_KHRONOS_validation and routes its messages to log().
    static Result<std::unique_ptr<VulkanInstance>> create(bool validation);
    ~VulkanInstance();
    VulkanInstance(const VulkanInstance&) = delete;
    VulkanInstance& operator=(const VulkanInstance&) = delete;

    VkInstance get() const { return instance_; }
    bool validation() const { return messenger_ != VK_NULL_HANDLE; }
    ValidationLog& log() { return log_; }

    // All devices, in loader order, each with its description (index = position).
    struct Device {
        VkPhysicalDevice handle = VK_NULL_HANDLE;
        DeviceInfo info;
    };
    Result<std::vector<Device>> devices() const;

private:
    VulkanInstance() = default;
    DeviceInfo describe(VkPhysicalDevice device, uint32_t index) const;

    VkInstance instance_ = VK_NULL_HANDLE;
    uint32_t api_version_ = VK_API_VERSION_1_0;  // what the instance was created with
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    PFN_vkDestroyDebugUtilsMessengerEXT destroy_messenger_ = nullptr;
    ValidationLog log_;  // address handed to the layer: the object lives on the heap and never moves
};

class VulkanContext {
public:
    static Result<std::unique_ptr<VulkanContext>> create(const EngineOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkDevice device() const { return device_; }
    VkPhysicalDevice physical_device() const { return physical_device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    const DeviceInfo& info() const { return info_; }
    const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
    const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_; }
    VkFormatFeatureFlags optimal_tiling_features(VkFormat format) const;

    // Where this context's buffers and images get their memory (and give it back).
    MemoryPool& memory_pool() const { return *memory_pool_; }

    bool validation() const { return instance_->validation(); }
    std::vector<std::string> take_validation_messages() { return instance_->log().take(); }

private:
    VulkanContext() = default;

    std::unique_ptr<VulkanInstance> instance_;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    DeviceInfo info_;
    VkDevice device_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::unique_ptr<MemoryPool> memory_pool_;  // emptied before the device goes
};

// One line from a batch of validation messages: the count and the first message.
Diagnostic validation_failure(std::string_view when, const std::vector<std::string>& messages);

}  // namespace crtforge::vulkan
