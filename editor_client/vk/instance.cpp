#include "editor_client/vk/instance.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "editor_client/vk/vk_result.h"

namespace lc::vk {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                VkDebugUtilsMessageTypeFlagsEXT types,
                                                const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                void* user_data) {
    auto* count = static_cast<std::atomic<uint32_t>*>(user_data);
    const char* text = data != nullptr && data->pMessage != nullptr ? data->pMessage : "(no text)";
    const bool error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
    // General warnings are the loader's notes (e.g. "layer forced enabled by
    // VK_LOADER_LAYERS_ENABLE"): printed, but they say nothing about our use of Vulkan.
    const bool about_our_usage = (types & (VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                           VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT)) != 0;
    if (error) {
        spdlog::error("vulkan validation: {}", text);
    } else if (about_our_usage) {
        spdlog::warn("vulkan validation: {}", text);
    } else {
        spdlog::info("vulkan loader: {}", text);
    }
    if (error || about_our_usage) count->fetch_add(1, std::memory_order_relaxed);
    return VK_FALSE;  // never abort the call: we count and report instead
}

bool layer_available(const char* name) {
    uint32_t count = 0;
    if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
    std::vector<VkLayerProperties> layers(count);
    if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
    return std::any_of(layers.begin(), layers.end(), [name](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

bool extension_available(const char* name) {
    uint32_t count = 0;
    if (vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr) != VK_SUCCESS)
        return false;
    std::vector<VkExtensionProperties> extensions(count);
    if (vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data()) != VK_SUCCESS)
        return false;
    return std::any_of(
        extensions.begin(), extensions.end(),
        [name](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

}  // namespace

bool validation_requested_by_environment() {
    const char* value = std::getenv("LC_VALIDATION");
    return value != nullptr && std::strcmp(value, "1") == 0;
}

Result<Instance> Instance::create(const InstanceOptions& options) {
    Instance result;
    result.counter_ = std::make_unique<MessageCounter>();

    bool want_validation = options.validation || validation_requested_by_environment();
    bool have_debug_utils = extension_available(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (want_validation && !layer_available(kValidationLayer)) {
        spdlog::warn("validation requested but {} is not installed; running without it",
                     kValidationLayer);
        want_validation = false;
    }
    result.validation_enabled_ = want_validation;

    std::vector<const char*> extensions;
    for (const std::string& name : options.extensions) {
        if (!extension_available(name.c_str()))
            return make_error("Vulkan instance extension " + name + " is not available");
        extensions.push_back(name.c_str());
    }
    if (have_debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    std::vector<const char*> layers;
    if (want_validation) layers.push_back(kValidationLayer);

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "editor_client";
    app.applicationVersion = VK_MAKE_VERSION(0, 1, 0);
    app.pEngineName = "lightcuts";
    app.apiVersion = VK_API_VERSION_1_3;

    VkDebugUtilsMessengerCreateInfoEXT messenger_info{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = on_debug_message;
    messenger_info.pUserData = &result.counter_->count;

    // Synchronization validation too: a missing barrier is as wrong as a bad
    // parameter, and lavapipe would rarely show it in the pixels.
    VkValidationFeatureEnableEXT enabled_features[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT validation_features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    validation_features.enabledValidationFeatureCount = 1;
    validation_features.pEnabledValidationFeatures = enabled_features;
    validation_features.pNext = have_debug_utils ? &messenger_info : nullptr;

    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    // Chained so messages from vkCreateInstance/vkDestroyInstance are counted too.
    info.pNext = have_debug_utils ? &messenger_info : nullptr;
    if (want_validation) info.pNext = &validation_features;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    LC_VK_CHECK(vkCreateInstance(&info, nullptr, &result.instance_));

    if (have_debug_utils) {
        auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(result.instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (create_messenger == nullptr)
            return make_error(
                "vkCreateDebugUtilsMessengerEXT is missing although "
                "VK_EXT_debug_utils is enabled");
        LC_VK_CHECK(
            create_messenger(result.instance_, &messenger_info, nullptr, &result.messenger_));
    }
    return result;
}

Instance::~Instance() { destroy(); }

Instance::Instance(Instance&& other) noexcept { *this = std::move(other); }

Instance& Instance::operator=(Instance&& other) noexcept {
    if (this != &other) {
        destroy();
        instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
        messenger_ = std::exchange(other.messenger_, VK_NULL_HANDLE);
        counter_ = std::move(other.counter_);
        validation_enabled_ = other.validation_enabled_;
    }
    return *this;
}

uint32_t Instance::validation_message_count() const {
    return counter_ ? counter_->count.load(std::memory_order_relaxed) : 0;
}

void Instance::destroy() {
    if (instance_ == VK_NULL_HANDLE) return;
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy_messenger != nullptr) destroy_messenger(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
}

}  // namespace lc::vk
