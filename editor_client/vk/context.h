#pragma once
// Everything a renderer needs from Vulkan before it creates its own resources:
// instance (+ validation), optional window surface, device and queue, and a
// command pool. Members are destroyed in reverse order of creation.
#include <vulkan/vulkan.h>

#include <functional>
#include <string>
#include <vector>

#include "editor_client/vk/command_pool.h"
#include "editor_client/vk/device.h"
#include "editor_client/vk/instance.h"
#include "editor_client/vk/physical_device.h"
#include "editor_client/vk/surface.h"
#include "lightcuts/result.h"

namespace lc::vk {

struct ContextOptions {
    bool validation = false;  // LC_VALIDATION=1 in the environment also enables it
    std::vector<std::string> instance_extensions;
    // Creates the window surface once the instance exists (empty: headless).
    std::function<Result<VkSurfaceKHR>(VkInstance)> create_surface;
};

class Context {
public:
    static Result<Context> create(const ContextOptions& options);

    const Instance& instance() const { return instance_; }
    VkSurfaceKHR surface() const { return surface_.handle(); }
    const Device& device() const { return device_; }
    const CommandPool& command_pool() const { return pool_; }
    const PhysicalDevice& physical() const { return device_.physical(); }

    uint32_t validation_message_count() const { return instance_.validation_message_count(); }
    bool validation_enabled() const { return instance_.validation_enabled(); }

private:
    Instance instance_;
    Surface surface_;
    Device device_;
    CommandPool pool_;
};

}  // namespace lc::vk
