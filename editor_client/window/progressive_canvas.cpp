#include "editor_client/window/progressive_canvas.h"

#include <algorithm>
#include <vector>

#include "editor_client/render/gpu/render_targets.h"
#include "editor_client/vk/barriers.h"

namespace lc::client {

Result<ProgressiveCanvas> ProgressiveCanvas::create(const vk::Device& device, uint32_t width,
                                                    uint32_t height) {
    // Sampled: only so that the view every vk::Image has is a valid one.
    Result<vk::Image> image = vk::Image::create(
        device, {width, height, kDisplayFormat,
                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    if (!image) return make_error("progressive canvas: " + image.error());
    ProgressiveCanvas canvas;
    canvas.image_ = std::move(image).value();
    return canvas;
}

void ProgressiveCanvas::record_tiles(VkCommandBuffer cmd, const vk::Image& display,
                                     std::span<const PixelRegion> tiles, uint32_t divisor) {
    // The canvas is written in TRANSFER_DST and rests in GENERAL between frames;
    // the tiles were written by compute, the canvas by earlier copies and read by presents.
    const VkImageLayout canvas_was = cleared_ ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED;
    vk::transition_image(cmd, {image_.handle(), canvas_was, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                               VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                               VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT});
    if (!cleared_) {
        const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &all);
        vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        cleared_ = true;
    }
    if (!tiles.empty()) blit_tiles(cmd, display, tiles, divisor);
    vk::transition_image(cmd, {image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                               VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                               kWriteStage, kWriteAccess});
}

void ProgressiveCanvas::blit_tiles(VkCommandBuffer cmd, const vk::Image& display,
                                   std::span<const PixelRegion> tiles, uint32_t divisor) {
    vk::transition_image(cmd, {display.handle(), VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                               VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT});
    const auto width = int32_t(image_.desc().width);
    const auto height = int32_t(image_.desc().height);
    const auto scale = int32_t(std::max(divisor, 1u));
    std::vector<VkImageBlit> regions;
    regions.reserve(tiles.size());
    for (const PixelRegion& t : tiles) {
        VkImageBlit r{};
        r.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        r.srcOffsets[0] = {int32_t(t.x), int32_t(t.y), 0};
        r.srcOffsets[1] = {int32_t(t.x + t.width), int32_t(t.y + t.height), 1};
        r.dstSubresource = r.srcSubresource;
        // A coarse pass's last row and column may reach past the canvas: clipped.
        r.dstOffsets[0] = {int32_t(t.x) * scale, int32_t(t.y) * scale, 0};
        r.dstOffsets[1] = {std::min(int32_t(t.x + t.width) * scale, width),
                           std::min(int32_t(t.y + t.height) * scale, height), 1};
        regions.push_back(r);
    }
    // Nearest: a coarse pass shows as blocks, the fine pass is copied exactly.
    vkCmdBlitImage(cmd, display.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image_.handle(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()), regions.data(), VK_FILTER_NEAREST);
    // Back to GENERAL, where the renderer and its read-backs expect it.
    vk::transition_image(cmd, {display.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                               VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0});
}

}  // namespace lc::client
