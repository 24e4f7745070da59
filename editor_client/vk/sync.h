#pragma once
// Fences and semaphores as owned handles.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

class Fence {
public:
    static Result<Fence> create(VkDevice device, bool signaled = false);

    VkFence handle() const { return fence_.get(); }
    // Waits (default: up to 10 minutes, longer than any render we do) then resets.
    Status wait_and_reset(uint64_t timeout_ns = 600'000'000'000ull) const;

private:
    DeviceHandle<VkFence> fence_;
};

class Semaphore {
public:
    static Result<Semaphore> create(VkDevice device);

    VkSemaphore handle() const { return semaphore_.get(); }

private:
    DeviceHandle<VkSemaphore> semaphore_;
};

}  // namespace lc::vk
