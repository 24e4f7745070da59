#pragma once
// Picks the GPU to render on: a real GPU when there is one (discrete first),
// otherwise a software rasteriser such as Mesa's lavapipe.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

#include "editor_client/vk/device_quirks.h"
#include "lightcuts/result.h"

namespace lc::vk {

struct PhysicalDevice {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    // One family does graphics, compute and transfer (and presents, when a surface was given).
    uint32_t queue_family = 0;
    uint32_t timestamp_valid_bits = 0;
    uint32_t subgroup_size = 1;  // lanes that share the lightcuts walk
    VkDriverId driver_id{};      // VkPhysicalDeviceDriverProperties (Vulkan 1.2)
    DeviceQuirks quirks;         // chosen from driver_id

    std::string name() const { return properties.deviceName; }
    bool is_software() const { return properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
};

// Requires Vulkan 1.3 with dynamic rendering, synchronization2 and subgroup
// votes in compute shaders; with a surface, also presentation support and
// VK_KHR_swapchain. The environment variable LC_VK_DEVICE (a substring of the
// device name) restricts the choice.
Result<PhysicalDevice> select_physical_device(VkInstance instance,
                                              VkSurfaceKHR surface = VK_NULL_HANDLE);

}  // namespace lc::vk
