#pragma once
// The logical device and its one queue (graphics + compute + transfer, and
// present when a swapchain is wanted).
#include <vulkan/vulkan.h>

#include <optional>

#include "editor_client/vk/physical_device.h"
#include "lightcuts/result.h"

namespace lc::vk {

class Device {
public:
    static Result<Device> create(const PhysicalDevice& physical, bool enable_swapchain);

    Device() = default;
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;
    Device(Device&& other) noexcept;
    Device& operator=(Device&& other) noexcept;

    VkDevice handle() const { return device_; }
    VkQueue queue() const { return queue_; }
    const PhysicalDevice& physical() const { return physical_; }
    uint32_t queue_family() const { return physical_.queue_family; }

    // A memory type allowed by type_bits with all `required` flags, preferring
    // one that also has `preferred`.
    std::optional<uint32_t> find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required,
                                             VkMemoryPropertyFlags preferred = 0) const;

    Status wait_idle() const;

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    PhysicalDevice physical_;
};

}  // namespace lc::vk
