#include "editor_client/vk/physical_device.h"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "editor_client/vk/vk_result.h"

namespace lc::vk {
namespace {

int type_preference(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return 3;
        default:
            return 4;
    }
}

bool has_device_extension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    for (const VkExtensionProperties& e : extensions)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// Empty when the device is usable, else why not.
std::string check_device(VkPhysicalDevice device, VkSurfaceKHR surface, PhysicalDevice& out) {
    out.handle = device;
    vkGetPhysicalDeviceProperties(device, &out.properties);
    vkGetPhysicalDeviceMemoryProperties(device, &out.memory);
    if (out.properties.apiVersion < VK_API_VERSION_1_3) return "Vulkan 1.3 is not supported";

    VkPhysicalDeviceVulkan13Features features13{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &features13;
    vkGetPhysicalDeviceFeatures2(device, &features);
    if (!features13.dynamicRendering) return "dynamicRendering is not supported";
    // The lightcuts walk votes across a subgroup (shaders/lightcuts_*.comp);
    // the shadow rays' shared walk broadcasts its stack entries (shadow_rays.glsl).
    VkPhysicalDeviceSubgroupProperties subgroup{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    subgroup.pNext = &driver;
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(device, &properties);
    out.driver_id = driver.driverID;
    out.quirks = quirks_for_driver(driver.driverID);
    if ((subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) == 0 ||
        (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_VOTE_BIT) == 0)
        return "subgroup vote operations in compute shaders are not supported";
    if ((subgroup.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT) == 0)
        return "subgroup ballot operations in compute shaders are not supported";
    out.subgroup_size = subgroup.subgroupSize;
    if (!features13.synchronization2) return "synchronization2 is not supported";
    if (surface != VK_NULL_HANDLE && !has_device_extension(device, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
        return "VK_KHR_swapchain is not supported";

    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    constexpr VkQueueFlags kNeeded = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    for (uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & kNeeded) != kNeeded) continue;
        if (surface != VK_NULL_HANDLE) {
            VkBool32 present = VK_FALSE;
            vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &present);
            if (!present) continue;
        }
        out.queue_family = i;
        out.timestamp_valid_bits = families[i].timestampValidBits;
        return {};
    }
    return surface != VK_NULL_HANDLE ? "no queue family does graphics, compute and presentation"
                                     : "no queue family does graphics and compute";
}

}  // namespace

Result<PhysicalDevice> select_physical_device(VkInstance instance, VkSurfaceKHR surface) {
    uint32_t count = 0;
    LC_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    if (count == 0) return make_error("no Vulkan device found (is mesa-vulkan-drivers installed?)");
    std::vector<VkPhysicalDevice> devices(count);
    LC_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));

    const char* wanted = std::getenv("LC_VK_DEVICE");
    std::string reasons;
    bool found = false;
    PhysicalDevice best;
    for (VkPhysicalDevice device : devices) {
        PhysicalDevice candidate;
        std::string problem = check_device(device, surface, candidate);
        if (problem.empty() && wanted != nullptr && *wanted != '\0' &&
            candidate.name().find(wanted) == std::string::npos)
            problem = std::string("its name does not contain LC_VK_DEVICE='") + wanted + "'";
        if (!problem.empty()) {
            reasons += "\n  " + candidate.name() + ": " + problem;
            continue;
        }
        if (!found || type_preference(candidate.properties.deviceType) <
                          type_preference(best.properties.deviceType)) {
            best = candidate;
            found = true;
        }
    }
    if (!found) return make_error("no usable Vulkan device:" + reasons);
    spdlog::debug("vulkan device: {}", best.name());
    return best;
}

}  // namespace lc::vk
