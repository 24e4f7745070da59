#include "editor_client/render/passes/output_pass.h"

#include "editor_client/vk/barriers.h"

namespace lc::client {

void OutputPass::record(VkCommandBuffer cmd, const Frame& frame) const {
    vk::memory_barrier(cmd, kComputeStage, kStorageWrite, kComputeStage,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    const VkImageLayout old_layout =
        frame.continues_image ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED;
    vk::transition_image(cmd, {frame.targets->display.handle(), old_layout,
                               VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                               VK_ACCESS_2_MEMORY_READ_BIT, kComputeStage, kStorageWrite});
    bind(cmd, frame);
    dispatch(cmd, frame, frame.constants);
}

}  // namespace lc::client
