#pragma once
// A command pool on the device's queue family, its command buffers (freed with
// the pool), and a one-time submit that waits for completion.
#include <vulkan/vulkan.h>

#include <functional>

#include "editor_client/vk/device.h"
#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

class CommandPool {
public:
    static Result<CommandPool> create(const Device& device);

    VkCommandPool handle() const { return pool_.get(); }

    // A primary command buffer that lives as long as the pool.
    Result<VkCommandBuffer> allocate() const;

    // Records `record` into a fresh command buffer, submits it and waits.
    Status run_one_time(const Device& device,
                        const std::function<void(VkCommandBuffer)>& record) const;

private:
    DeviceHandle<VkCommandPool> pool_;
};

}  // namespace lc::vk
