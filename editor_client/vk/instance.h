#pragma once
// The Vulkan instance, with the Khronos validation layer and a debug messenger
// that prints and counts every warning and error it reports (tests assert the
// count is zero).
#include <vulkan/vulkan.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "lightcuts/result.h"

namespace lc::vk {

struct InstanceOptions {
    // Enables validation even without LC_VALIDATION=1 in the environment.
    bool validation = false;
    // Extensions a window system needs (VK_KHR_surface and its platform extension).
    std::vector<std::string> extensions;
};

// True when the environment asks for validation (LC_VALIDATION=1).
bool validation_requested_by_environment();

class Instance {
public:
    static Result<Instance> create(const InstanceOptions& options);

    Instance() = default;
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;
    Instance(Instance&& other) noexcept;
    Instance& operator=(Instance&& other) noexcept;

    VkInstance handle() const { return instance_; }
    // The validation layer was requested and found.
    bool validation_enabled() const { return validation_enabled_; }
    // Validation warnings and errors (and any error) reported so far; the
    // loader's general warnings are logged but not counted.
    uint32_t validation_message_count() const;

private:
    void destroy();

    // Heap-allocated so the messenger's user-data pointer survives moves.
    struct MessageCounter {
        std::atomic<uint32_t> count{0};
    };

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    std::unique_ptr<MessageCounter> counter_;
    bool validation_enabled_ = false;
};

}  // namespace lc::vk
