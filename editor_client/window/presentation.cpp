#include "editor_client/window/presentation.h"

#include <utility>

#include "editor_client/vk/barriers.h"

namespace lc::client {

Result<Presentation> make_presentation(const vk::Context& context, VkExtent2D extent, Presentation* old) {
    Presentation p;
    Result<vk::Swapchain> swapchain = vk::Swapchain::create(context.device(), context.surface(), extent,
                                                            old != nullptr ? &old->swapchain : nullptr);
    if (!swapchain) return make_error(swapchain.error());
    p.swapchain = std::move(swapchain).value();
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(context.physical().handle, p.swapchain.format(), &props);
    if ((props.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) == 0)
        return make_error("the swapchain format cannot be a blit destination");
    for (size_t i = 0; i < p.swapchain.images().size(); ++i) {
        Result<vk::Semaphore> s = vk::Semaphore::create(context.device().handle());
        if (!s) return make_error(s.error());
        p.rendered.push_back(std::move(s).value());
    }
    return p;
}

void record_blit(VkCommandBuffer cmd, const vk::Image& display, VkImage target, VkExtent2D extent,
                 bool keep_target_for_drawing) {
    vk::transition_image(cmd,
                         {display.handle(), VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT});
    // The acquire semaphore is waited at the blit stage, so the layout change
    // chains after it.
    vk::transition_image(
        cmd, {target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
              VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT});
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {int32_t(display.desc().width), int32_t(display.desc().height), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
    vkCmdBlitImage(cmd, display.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_LINEAR);
    if (keep_target_for_drawing) {
        vk::transition_image(
            cmd, {target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT});
    } else {
        vk::transition_image(
            cmd, {target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                  VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_NONE, 0});
    }
    // Back to GENERAL, where the renderer and its read-backs expect it.
    vk::transition_image(cmd,
                         {display.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                          VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0});
}

}  // namespace lc::client
