#include "editor_client/render/gpu/render_targets.h"

#include <algorithm>
#include <string>

#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

// Storage use of RG32UI and RGBA32F, and RGBA32F attachments, are optional in
// Vulkan: say which one is missing rather than fail in a driver.
Status check_format(const vk::Device& device, VkFormat format, VkFormatFeatureFlags needed,
                    const char* what) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(device.physical().handle, format, &props);
    if ((props.optimalTilingFeatures & needed) != needed)
        return make_error(std::string("the device cannot use ") + what);
    return Ok{};
}

}  // namespace

Result<RenderTargets> RenderTargets::create(const vk::Device& device, uint32_t width,
                                            uint32_t height) {
    LC_RETURN_IF_ERROR(
        check_format(device, kGBufferFormat,
                     VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT,
                     "RGBA32F images as colour attachments and storage images (the G-buffer)"));
    LC_RETURN_IF_ERROR(check_format(device, kCutFormat, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT,
                                    "RG32UI storage images (the cut image)"));
    LC_RETURN_IF_ERROR(check_format(device, kDepthFormat,
                                    VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                    "D32 depth attachments"));
    RenderTargets targets;
    targets.width = width;
    targets.height = height;
    auto make = [&](vk::Image& out, VkFormat format, VkImageUsageFlags usage,
                    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT) -> Status {
        Result<vk::Image> image = vk::Image::create(device, {width, height, format, usage, aspect});
        if (!image) return make_error(image.error());
        out = std::move(image).value();
        return Ok{};
    };
    constexpr VkImageUsageFlags kGBufferUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                                VK_IMAGE_USAGE_STORAGE_BIT |
                                                VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    constexpr VkImageUsageFlags kStorageUsage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    for (vk::Image* image :
         {&targets.position, &targets.normal, &targets.albedo, &targets.emissive}) {
        Status made = make(*image, kGBufferFormat, kGBufferUsage);
        if (!made) return make_error(made.error());
    }
    for (Status made :
         {make(targets.depth, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
               VK_IMAGE_ASPECT_DEPTH_BIT),
          make(targets.hdr, kHdrFormat, kStorageUsage),
          make(targets.cut, kCutFormat, kStorageUsage),
          make(targets.display, kDisplayFormat, kStorageUsage)}) {
        if (!made) return make_error(made.error());
    }
    // Per pixel for the walk search; at least kReferenceScratch entries, where
    // reference mode keeps the sums of a small image's parts
    // (passes/reference_pass.cpp): 64 parts of an 8x8 image.
    constexpr VkDeviceSize kReferenceScratch = 4096;
    Result<vk::Buffer> walk_states = vk::Buffer::create(
        device, std::max(VkDeviceSize(width) * height, kReferenceScratch) * sizeof(GpuWalkState),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kDeviceLocal);
    if (!walk_states) return make_error(walk_states.error());
    targets.walk_states = std::move(walk_states).value();
    return targets;
}

}  // namespace lc::client
