#pragma once
// What a driver does differently from the Vulkan specification's ideal
// device, chosen by its driver id (never by the device name, which changes
// with the CPU or the Mesa version).
#include <vulkan/vulkan.h>

#include <cstdint>

namespace lc::vk {

struct DeviceQuirks {
    // Loop iterations (back edges of all loops together) after which the
    // driver stops an invocation's loops without a word; 0: no limit.
    // llvmpipe's is 65,535 (shaders/lightcuts/device/limits.h).
    uint32_t loop_iteration_limit = 0;

    bool has_loop_limit() const { return loop_iteration_limit != 0; }
};

DeviceQuirks quirks_for_driver(VkDriverId driver);

}  // namespace lc::vk
