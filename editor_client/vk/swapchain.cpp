#include "editor_client/vk/swapchain.h"

#include <algorithm>

#include "editor_client/vk/vk_result.h"

namespace lc::vk {
namespace {

VkSurfaceFormatKHR choose_format(const std::vector<VkSurfaceFormatKHR>& formats) {
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM}) {
        for (const VkSurfaceFormatKHR& f : formats)
            if (f.format == wanted) return f;
    }
    return formats.front();
}

}  // namespace

Result<Swapchain> Swapchain::create(const Device& device, VkSurfaceKHR surface, VkExtent2D wanted,
                                    Swapchain* old) {
    VkPhysicalDevice physical = device.physical().handle;
    VkSurfaceCapabilitiesKHR caps;
    LC_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps));
    uint32_t count = 0;
    LC_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr));
    if (count == 0) return make_error("the window surface offers no formats");
    std::vector<VkSurfaceFormatKHR> formats(count);
    LC_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data()));
    VkSurfaceFormatKHR format = choose_format(formats);
    if ((caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) == 0)
        return make_error("the window surface cannot be a transfer destination (needed to blit)");

    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {
        extent.width =
            std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height =
            std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    if (extent.width == 0 || extent.height == 0) return make_error("the window has zero size");
    uint32_t image_count = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface;
    info.minImageCount = image_count;
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if ((caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR) == 0)
        info.compositeAlpha = VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // the one mode every driver supports
    info.clipped = VK_TRUE;
    info.oldSwapchain = old != nullptr ? old->handle() : VK_NULL_HANDLE;
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateSwapchainKHR(device.handle(), &info, nullptr, &handle));

    Swapchain result;
    result.swapchain_ =
        DeviceHandle<VkSwapchainKHR>(device.handle(), handle, vkDestroySwapchainKHR);
    result.format_ = format.format;
    result.extent_ = extent;
    LC_VK_CHECK(vkGetSwapchainImagesKHR(device.handle(), handle, &count, nullptr));
    result.images_.resize(count);
    LC_VK_CHECK(vkGetSwapchainImagesKHR(device.handle(), handle, &count, result.images_.data()));
    return result;
}

Result<AcquireStatus> Swapchain::acquire(VkSemaphore ready, uint32_t& image_index) const {
    VkResult r = vkAcquireNextImageKHR(swapchain_.device(), swapchain_.get(), UINT64_MAX, ready,
                                       VK_NULL_HANDLE, &image_index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) return AcquireStatus::kOutOfDate;
    if (r != VK_SUCCESS && r != VK_SUBOPTIMAL_KHR) return call_failed(r, "vkAcquireNextImageKHR");
    return AcquireStatus::kReady;
}

Result<AcquireStatus> Swapchain::present(VkQueue queue, VkSemaphore rendered,
                                         uint32_t image_index) const {
    VkSwapchainKHR handle = swapchain_.get();
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &rendered;
    info.swapchainCount = 1;
    info.pSwapchains = &handle;
    info.pImageIndices = &image_index;
    VkResult r = vkQueuePresentKHR(queue, &info);
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return AcquireStatus::kOutOfDate;
    if (r != VK_SUCCESS) return call_failed(r, "vkQueuePresentKHR");
    return AcquireStatus::kReady;
}

}  // namespace lc::vk
