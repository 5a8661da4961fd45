// Turning VkResult codes into crtforge diagnostics.
#pragma once

#include <string_view>

#include <vulkan/vulkan.h>

#include "crtforge/diagnostic.hpp"

namespace crtforge::vulkan {

// "VK_ERROR_OUT_OF_DEVICE_MEMORY", or "VkResult(-13)" for codes this build does not name.
std::string vk_result_name(VkResult result);

// One-line error for a failed Vulkan call: "vkCreateBuffer failed: VK_ERROR_OUT_OF_DEVICE_MEMORY".
Diagnostic vk_error(std::string_view call, VkResult result);

}  // namespace crtforge::vulkan
