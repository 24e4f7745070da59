#pragma once
// What the progressive editor shows: a full-size 8-bit image that each
// frame's finished tiles are copied onto, scaled up from a coarse pass, so the
// window holds the coarse image under the fine tiles while they refine (the
// renderer's own images hold one pass at a time).
#include <vulkan/vulkan.h>

#include <span>

#include "editor_client/render/gpu/pixel_region.h"
#include "editor_client/vk/device.h"
#include "editor_client/vk/image.h"
#include "lightcuts/result.h"

namespace lc::client {

class ProgressiveCanvas {
public:
    static Result<ProgressiveCanvas> create(const vk::Device& device, uint32_t width, uint32_t height);

    // Copies `tiles` of `display` (GENERAL, written by compute; 1/divisor of the
    // canvas's size) onto the canvas, each scaled by `divisor`. The first call
    // clears the canvas to black first. The canvas stays in GENERAL.
    void record_tiles(VkCommandBuffer cmd, const vk::Image& display, std::span<const PixelRegion> tiles,
                      uint32_t divisor);

    const vk::Image& image() const { return image_; }
    // The stage and access of the canvas's last write (a blit), for what reads it next.
    static constexpr VkPipelineStageFlags2 kWriteStage = VK_PIPELINE_STAGE_2_BLIT_BIT;
    static constexpr VkAccessFlags2 kWriteAccess = VK_ACCESS_2_TRANSFER_WRITE_BIT;

private:
    void blit_tiles(VkCommandBuffer cmd, const vk::Image& display, std::span<const PixelRegion> tiles,
                    uint32_t divisor);

    vk::Image image_;
    bool cleared_ = false;
};

}  // namespace lc::client
