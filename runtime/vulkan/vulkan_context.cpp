#include "runtime/vulkan/vulkan_context.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <unistd.h>
#include <mutex>
#include <iostream>

#include <fmt/core.h>

#include "runtime/vulkan/vulkan_check.hpp"

namespace crtforge::vulkan {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr VkDeviceSize kKeptMemoryBytes = VkDeviceSize{512} << 20;  // freed memory a context keeps for reuse
constexpr const char* kLavapipeHint = "install mesa-vulkan-drivers for the lavapipe CPU device";

std::string lowercase(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string version_string(uint32_t version) {
    return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version),
                       VK_API_VERSION_PATCH(version));
}

const char* device_type_name(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
        default: return "other";
    }
}

const char* severity_name(VkDebugUtilsMessageSeverityFlagBitsEXT severity) {
    return (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user_data) {
    // Called from inside the driver stack: nothing may throw across it.
    try {
        const char* text = (data && data->pMessage) ? data->pMessage : "(no message text)";
        const std::string message = fmt::format("{}: {}", severity_name(severity), text);
        // The loader's own messages (e.g. a stale ICD manifest of an uninstalled driver) describe
        // the machine's Vulkan install, not the work being validated: say them, do not fail on them.
        if (data && data->pMessageIdName && std::strcmp(data->pMessageIdName, "Loader Message") == 0) {
            std::cerr << "crtforge: note from the Vulkan loader: " << message << '\n';
        } else {
            static_cast<ValidationLog*>(user_data)->add(message);
        }
    } catch (...) {
    }
    return VK_FALSE;  // never abort the call: the engine decides what a message means
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationLog* log) {
    VkDebugUtilsMessengerCreateInfoEXT info{};
    info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    // Warnings count as failures too: a shader the harness blesses must be clean, not "mostly".
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_validation_message;
    info.pUserData = log;
    return info;
}

bool has_layer(const char* name) {
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(count);
    if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

// Whether the loader itself or the named layer provides an instance extension.
bool has_instance_extension(const char* name, const char* layer) {
    auto listed_by = [name](const char* source) {
        uint32_t count = 0;
        if (vkEnumerateInstanceExtensionProperties(source, &count, nullptr) != VK_SUCCESS) return false;
        std::vector<VkExtensionProperties> extensions(count);
        if (vkEnumerateInstanceExtensionProperties(source, &count, extensions.data()) != VK_SUCCESS) return false;
        return std::any_of(extensions.begin(), extensions.end(),
                           [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
    };
    return listed_by(nullptr) || listed_by(layer);
}

bool has_device_extension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    if (vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkExtensionProperties> extensions(count);
    if (vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()) != VK_SUCCESS) return false;
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// The highest instance version worth asking for: 1.2 lets device listing read the driver name
// (VkPhysicalDeviceDriverProperties) and lets shaders be SPIR-V up to 1.5. The engine's own calls
// are all Vulkan 1.0.
uint32_t pick_instance_version() {
    auto enumerate_version = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
        vkGetInstanceProcAddr(VK_NULL_HANDLE, "vkEnumerateInstanceVersion"));
    uint32_t loader = VK_API_VERSION_1_0;
    if (enumerate_version && enumerate_version(&loader) != VK_SUCCESS) loader = VK_API_VERSION_1_0;
    return std::min(loader, VK_API_VERSION_1_2);
}

bool is_lavapipe(const DeviceInfo& info) {
    return lowercase(info.name).find("llvmpipe") != std::string::npos ||
           lowercase(info.driver).find("llvmpipe") != std::string::npos;
}

std::string describe_all(const std::vector<VulkanInstance::Device>& devices) {
    std::string out;
    for (const auto& d : devices) {
        if (!out.empty()) out += ", ";
        out += fmt::format("{}: {} ({})", d.info.index, d.info.name, d.info.type);
    }
    return out;
}

// "" -> lavapipe if present, else the first device; digits -> index; text -> name substring.
Result<size_t> select_device(const std::vector<VulkanInstance::Device>& devices, const std::string& wanted) {
    if (wanted.empty()) {
        for (size_t i = 0; i < devices.size(); ++i) {
            if (is_lavapipe(devices[i].info)) return i;
        }
        return size_t{0};
    }
    if (std::all_of(wanted.begin(), wanted.end(), [](unsigned char c) { return std::isdigit(c); })) {
        size_t index = 0;
        for (char c : wanted) {
            index = index * 10 + static_cast<size_t>(c - '0');
            if (index >= devices.size()) break;  // also stops overflow on absurd inputs
        }
        if (index < devices.size()) return index;
        return make_error(fmt::format("no Vulkan device with index {}; available: {}", wanted, describe_all(devices)),
                          {}, 0, "device");
    }
    const std::string needle = lowercase(wanted);
    for (size_t i = 0; i < devices.size(); ++i) {
        if (lowercase(devices[i].info.name).find(needle) != std::string::npos) return i;
    }
    return make_error(fmt::format("no Vulkan device name contains '{}'; available: {}", wanted, describe_all(devices)),
                      {}, 0, "device");
}

Result<uint32_t> graphics_queue_family(VkPhysicalDevice device, const DeviceInfo& info) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && families[i].queueCount > 0) return i;
    }
    return make_error(fmt::format("Vulkan device '{}' has no graphics queue", info.name), {}, 0, "device");
}

}  // namespace

// ---- ValidationLog ---------------------------------------------------------------------------

void ValidationLog::add(std::string message) {
    std::lock_guard lock(mutex_);
    messages_.push_back(std::move(message));
}

std::vector<std::string> ValidationLog::take() {
    std::lock_guard lock(mutex_);
    return std::exchange(messages_, {});
}

Diagnostic validation_failure(std::string_view when, const std::vector<std::string>& messages) {
    return make_error(fmt::format("Vulkan validation reported {} message(s) {}; first: {}", messages.size(), when,
                                  messages.empty() ? std::string() : messages.front()));
}

// ---- VulkanInstance --------------------------------------------------------------------------

namespace {

// SwiftShader's Vulkan driver (Debian's chromium-common) keeps its ICD file beside Chromium,
// where the loader does not look. When it is installed and the user has not chosen the drivers
// (VK_ICD_FILENAMES / VK_DRIVER_FILES), it is added to the loader's list, so `--device
// SwiftShader` and validate's second driver find it. Done once, before the first instance.
void add_known_drivers() {
    static std::once_flag once;
    std::call_once(once, [] {
        constexpr const char* kSwiftShader = "/usr/lib/chromium/vk_swiftshader_icd.json";
        if (std::getenv("VK_ICD_FILENAMES") || std::getenv("VK_DRIVER_FILES")) return;
        if (::access(kSwiftShader, R_OK) != 0) return;
        std::string add = kSwiftShader;
        if (const char* more = std::getenv("VK_ADD_DRIVER_FILES"); more && *more) add = std::string(more) + ":" + add;
        ::setenv("VK_ADD_DRIVER_FILES", add.c_str(), 1);
    });
}

}  // namespace

Result<std::unique_ptr<VulkanInstance>> VulkanInstance::create(bool validation) {
    add_known_drivers();
    std::unique_ptr<VulkanInstance> self(new VulkanInstance);  // destructor cleans up partial state

    std::vector<const char*> layers, extensions;
    if (validation) {
        if (!has_layer(kValidationLayer)) {
            return make_error(fmt::format("Vulkan validation was requested but {} is not installed: "
                                          "install vulkan-validationlayers",
                                          kValidationLayer));
        }
        if (!has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME, kValidationLayer)) {
            return make_error("Vulkan validation was requested but VK_EXT_debug_utils is unavailable, so its "
                              "messages cannot be collected: install vulkan-validationlayers");
        }
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }

    self->api_version_ = pick_instance_version();
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "crtforge";
    app.pEngineName = "crtforge";
    app.apiVersion = self->api_version_;

    // Chained into the create info so messages from vkCreateInstance/vkDestroyInstance are caught too.
    VkDebugUtilsMessengerCreateInfoEXT debug = messenger_info(&self->log_);
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pNext = validation ? &debug : nullptr;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();

    if (VkResult r = vkCreateInstance(&info, nullptr, &self->instance_); r != VK_SUCCESS) {
        self->instance_ = VK_NULL_HANDLE;
        if (r == VK_ERROR_INCOMPATIBLE_DRIVER) {
            return make_error(fmt::format("no Vulkan driver found (vkCreateInstance: {}): {}", vk_result_name(r),
                                          kLavapipeHint));
        }
        return make_error(fmt::format("cannot create a Vulkan instance (vkCreateInstance: {}): check that libvulkan1 "
                                      "and mesa-vulkan-drivers are installed",
                                      vk_result_name(r)));
    }

    if (validation) {
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(self->instance_, "vkCreateDebugUtilsMessengerEXT"));
        self->destroy_messenger_ = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(self->instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (!create_messenger || !self->destroy_messenger_) {
            return make_error("Vulkan validation: vkCreateDebugUtilsMessengerEXT is unavailable");
        }
        if (VkResult r = create_messenger(self->instance_, &debug, nullptr, &self->messenger_); r != VK_SUCCESS) {
            self->messenger_ = VK_NULL_HANDLE;
            return vk_error("vkCreateDebugUtilsMessengerEXT", r);
        }
    }
    return self;
}

VulkanInstance::~VulkanInstance() {
    if (messenger_ != VK_NULL_HANDLE) destroy_messenger_(instance_, messenger_, nullptr);
    if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
    // Nobody is left to return these to; say them rather than drop them (e.g. leaked objects).
    for (const auto& message : log_.take()) std::cerr << "crtforge: Vulkan validation at shutdown: " << message << '\n';
}

Result<std::vector<VulkanInstance::Device>> VulkanInstance::devices() const {
    uint32_t count = 0;
    if (VkResult r = vkEnumeratePhysicalDevices(instance_, &count, nullptr); r != VK_SUCCESS) {
        return vk_error("vkEnumeratePhysicalDevices", r);
    }
    std::vector<VkPhysicalDevice> handles(count);
    if (VkResult r = vkEnumeratePhysicalDevices(instance_, &count, handles.data()); r != VK_SUCCESS && r != VK_INCOMPLETE) {
        return vk_error("vkEnumeratePhysicalDevices", r);
    }
    handles.resize(count);
    if (handles.empty()) return make_error(fmt::format("the Vulkan loader found no device: {}", kLavapipeHint));

    std::vector<Device> out;
    for (uint32_t i = 0; i < handles.size(); ++i) out.push_back(Device{handles[i], describe(handles[i], i)});
    return out;
}

DeviceInfo VulkanInstance::describe(VkPhysicalDevice device, uint32_t index) const {
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(device, &props);
    DeviceInfo info;
    info.index = index;
    info.name = props.deviceName;
    info.type = device_type_name(props.deviceType);

    // The driver's own name needs VkPhysicalDeviceDriverProperties (Vulkan 1.2, or the KHR extension
    // on older drivers); without it the raw IDs are all there is.
    const uint32_t usable = std::min(api_version_, props.apiVersion);
    const bool driver_props = usable >= VK_API_VERSION_1_2 ||
                              (usable >= VK_API_VERSION_1_1 &&
                               has_device_extension(device, VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME));
    if (driver_props) {
        VkPhysicalDeviceDriverProperties driver{};
        driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
        VkPhysicalDeviceProperties2 props2{};
        props2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
        props2.pNext = &driver;
        vkGetPhysicalDeviceProperties2(device, &props2);
        info.driver = driver.driverInfo[0] ? fmt::format("{} ({})", driver.driverName, driver.driverInfo)
                                           : std::string(driver.driverName);
    } else {
        info.driver = fmt::format("vendor 0x{:04x}, driver version 0x{:08x}, Vulkan {}", props.vendorID,
                                  props.driverVersion, version_string(props.apiVersion));
    }
    return info;
}

// ---- VulkanContext ---------------------------------------------------------------------------

Result<std::unique_ptr<VulkanContext>> VulkanContext::create(const EngineOptions& options) {
    std::unique_ptr<VulkanContext> self(new VulkanContext);

    auto instance = VulkanInstance::create(options.validation);
    if (!instance) return instance.error();
    self->instance_ = std::move(instance).value();

    auto devices = self->instance_->devices();
    if (!devices) return devices.error();
    auto chosen = select_device(devices.value(), options.device);
    if (!chosen) return chosen.error();
    const auto& device = devices.value()[chosen.value()];

    self->physical_device_ = device.handle;
    self->info_ = device.info;
    vkGetPhysicalDeviceProperties(device.handle, &self->properties_);
    vkGetPhysicalDeviceMemoryProperties(device.handle, &self->memory_);

    auto family = graphics_queue_family(device.handle, device.info);
    if (!family) return family.error();
    self->queue_family_ = family.value();

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = self->queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;

    // No features, no extensions: a full-screen pass needs nothing beyond Vulkan 1.0, which keeps
    // every conformant device (and every older lavapipe) usable.
    VkDeviceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    if (VkResult r = vkCreateDevice(self->physical_device_, &info, nullptr, &self->device_); r != VK_SUCCESS) {
        self->device_ = VK_NULL_HANDLE;
        return make_error(fmt::format("cannot open Vulkan device '{}': vkCreateDevice failed: {}", self->info_.name,
                                      vk_result_name(r)));
    }
    vkGetDeviceQueue(self->device_, self->queue_family_, 0, &self->queue_);
    self->memory_pool_ = std::make_unique<MemoryPool>(self->device_, kKeptMemoryBytes);

    if (auto messages = self->take_validation_messages(); !messages.empty()) {
        return validation_failure("while opening the device", messages);
    }
    return self;
}

VulkanContext::~VulkanContext() {
    if (device_ != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(device_);
        memory_pool_.reset();
        vkDestroyDevice(device_, nullptr);
    }
    // instance_ (and its messenger) goes last, as a member.
}

VkFormatFeatureFlags VulkanContext::optimal_tiling_features(VkFormat format) const {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(physical_device_, format, &props);
    return props.optimalTilingFeatures;
}

}  // namespace crtforge::vulkan

// ---- public: device listing ------------------------------------------------------------------

namespace crtforge {

Result<std::vector<DeviceInfo>> list_vulkan_devices() {
    try {
        auto instance = vulkan::VulkanInstance::create(false);
        if (!instance) return instance.error();
        auto devices = instance.value()->devices();
        if (!devices) return devices.error();
        std::vector<DeviceInfo> out;
        for (auto& d : devices.value()) out.push_back(std::move(d.info));
        return out;
    } catch (const std::exception& e) {  // bad_alloc and the like: errors are values here
        return make_error(std::string("listing Vulkan devices failed: ") + e.what());
    }
}

Result<std::string> vulkan_device_named(const std::string& part, const std::string& besides) {
    auto devices = list_vulkan_devices();
    if (!devices.ok()) return devices.error();
    auto lower = [](std::string t) {
        for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return t;
    };
    for (const DeviceInfo& d : devices.value()) {
        if (lower(d.name).find(lower(part)) == std::string::npos) continue;
        if (!besides.empty() && lower(d.name).find(lower(besides)) != std::string::npos) continue;
        return d.name;
    }
    return std::string();
}

}  // namespace crtforge
