#pragma once
// The swapchain side of a frame loop, shared by the plain view loop and the
// editor loop: the swapchain with one "rendered" semaphore per image, and the
// blit that scales the renderer's display image onto a swapchain image.
#include <vulkan/vulkan.h>

#include <optional>
#include <vector>

#include "editor_client/vk/context.h"
#include "editor_client/vk/image.h"
#include "editor_client/vk/swapchain.h"
#include "editor_client/vk/sync.h"
#include "lightcuts/result.h"

namespace lc::client {

// Per-swapchain objects: a present may still wait on the previous semaphore
// of another image, so each image has its own.
struct Presentation {
    vk::Swapchain swapchain;
    std::vector<vk::Semaphore> rendered;
};

Result<Presentation> make_presentation(const vk::Context& context, VkExtent2D extent, Presentation* old);

// How the image to show was last written (the renderer's compute passes, or
// the progressive canvas's copies).
struct DisplayWrite {
    VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    VkAccessFlags2 access = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
};

// Scales `display` (GENERAL) onto `target` and leaves `target` ready to
// present and `display` back in GENERAL. With `keep_target_for_drawing`,
// `target` ends in COLOR_ATTACHMENT_OPTIMAL instead so a UI pass can draw over
// it (the pass then moves it to PRESENT_SRC).
void record_blit(VkCommandBuffer cmd, const vk::Image& display, VkImage target, VkExtent2D extent,
                 bool keep_target_for_drawing = false, DisplayWrite written = {});

// Makes `presentation` match `extent`: (re)creates it when absent, when its
// size differs, or when `recreate` is set (then cleared). True when it was made anew.
Result<bool> ensure_presentation(const vk::Context& context, VkExtent2D extent,
                                 std::optional<Presentation>& presentation, bool& recreate);

// Acquires the next swapchain image into `image_index`, signalling
// `image_ready`. True: the swapchain is out of date (recreate, skip the frame).
Result<bool> acquire_image(Presentation& presentation, const vk::Semaphore& image_ready,
                           uint32_t& image_index);

// Resets `cmd` and begins it for one submission: a frame's commands.
Status begin_frame_commands(VkCommandBuffer cmd);

// Submits one frame's commands and, with a presentation, presents swapchain
// image `image_index` once they finish (waiting on `image_ready`, the acquire
// semaphore). Waits for `frame_done`. True: the swapchain is out of date.
Result<bool> submit_and_present(const vk::Device& device, Presentation* presentation, VkCommandBuffer cmd,
                                const vk::Semaphore& image_ready, uint32_t image_index,
                                const vk::Fence& frame_done);

}  // namespace lc::client
