#pragma once
// The window's swapchain. We blit an already tone-mapped, sRGB-encoded RGBA8
// image into it, so it prefers a UNORM format (no second sRGB encode).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "editor_client/vk/device.h"
#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

enum class AcquireStatus { kReady, kOutOfDate };

class Swapchain {
public:
    // `old` (may be null) is retired by the new swapchain.
    static Result<Swapchain> create(const Device& device, VkSurfaceKHR surface, VkExtent2D wanted,
                                    Swapchain* old = nullptr);

    VkSwapchainKHR handle() const { return swapchain_.get(); }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    const std::vector<VkImage>& images() const { return images_; }

    // Acquires the next image, signalling `ready` when it may be written.
    Result<AcquireStatus> acquire(VkSemaphore ready, uint32_t& image_index) const;
    // Presents after `rendered` is signalled; kOutOfDate asks for a new swapchain.
    Result<AcquireStatus> present(VkQueue queue, VkSemaphore rendered, uint32_t image_index) const;

private:
    DeviceHandle<VkSwapchainKHR> swapchain_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{0, 0};
    std::vector<VkImage> images_;  // owned by the swapchain
};

}  // namespace lc::vk
