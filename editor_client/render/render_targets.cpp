#include "editor_client/render/render_targets.h"

namespace lc::client {

Result<RenderTargets> RenderTargets::create(const vk::Device& device, uint32_t width,
                                            uint32_t height) {
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
    return targets;
}

}  // namespace lc::client
