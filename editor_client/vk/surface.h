#pragma once
// A window surface, owned together with the instance handle it came from.
#include <vulkan/vulkan.h>

#include <utility>

namespace lc::vk {

class Surface {
public:
    Surface() = default;
    Surface(VkInstance instance, VkSurfaceKHR surface) : instance_(instance), surface_(surface) {}
    ~Surface() { reset(); }
    Surface(const Surface&) = delete;
    Surface& operator=(const Surface&) = delete;
    Surface(Surface&& other) noexcept { *this = std::move(other); }
    Surface& operator=(Surface&& other) noexcept {
        if (this != &other) {
            reset();
            instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
            surface_ = std::exchange(other.surface_, VK_NULL_HANDLE);
        }
        return *this;
    }

    VkSurfaceKHR handle() const { return surface_; }

    void reset() {
        if (surface_ != VK_NULL_HANDLE) vkDestroySurfaceKHR(instance_, surface_, nullptr);
        surface_ = VK_NULL_HANDLE;
    }

private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

}  // namespace lc::vk
