#include "editor_client/window/presentation.h"

#include <utility>

#include "editor_client/vk/barriers.h"
#include "editor_client/vk/vk_result.h"

namespace lc::client {

Result<bool> acquire_image(Presentation& presentation, const vk::Semaphore& image_ready,
                           uint32_t& image_index) {
    Result<vk::AcquireStatus> acquired = presentation.swapchain.acquire(image_ready.handle(), image_index);
    if (!acquired) return make_error(acquired.error());
    return *acquired == vk::AcquireStatus::kOutOfDate;
}

Status begin_frame_commands(VkCommandBuffer cmd) {
    LC_VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    LC_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    return Ok{};
}

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
                 bool keep_target_for_drawing, DisplayWrite written) {
    vk::transition_image(cmd, {display.handle(), VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               written.stage, written.access, VK_PIPELINE_STAGE_2_BLIT_BIT,
                               VK_ACCESS_2_TRANSFER_READ_BIT});
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

Result<bool> ensure_presentation(const vk::Context& context, VkExtent2D extent,
                                 std::optional<Presentation>& presentation, bool& recreate) {
    if (presentation && (presentation->swapchain.extent().width != extent.width ||
                         presentation->swapchain.extent().height != extent.height))
        recreate = true;
    if (presentation && !recreate) return false;
    LC_RETURN_IF_ERROR(context.device().wait_idle());
    Result<Presentation> next = make_presentation(context, extent, presentation ? &*presentation : nullptr);
    if (!next) return make_error(next.error());
    presentation = std::move(next).value();
    recreate = false;
    return true;
}

Result<bool> submit_and_present(const vk::Device& device, Presentation* presentation, VkCommandBuffer cmd,
                                const vk::Semaphore& image_ready, uint32_t image_index,
                                const vk::Fence& frame_done) {
    const bool presenting = presentation != nullptr;
    VkSemaphore wait = image_ready.handle();
    VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSemaphore signal = presenting ? presentation->rendered[image_index].handle() : VK_NULL_HANDLE;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = presenting ? 1 : 0;
    submit.pWaitSemaphores = &wait;
    submit.pWaitDstStageMask = &wait_stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    submit.signalSemaphoreCount = presenting ? 1 : 0;
    submit.pSignalSemaphores = &signal;
    LC_VK_CHECK(vkQueueSubmit(device.queue(), 1, &submit, frame_done.handle()));
    bool out_of_date = false;
    if (presenting) {
        Result<vk::AcquireStatus> presented = presentation->swapchain.present(device.queue(), signal, image_index);
        if (!presented) return make_error(presented.error());
        out_of_date = *presented == vk::AcquireStatus::kOutOfDate;
    }
    LC_RETURN_IF_ERROR(frame_done.wait_and_reset());
    return out_of_date;
}

}  // namespace lc::client
