#pragma once
// Pipeline barriers (synchronization2) for the few transitions we need.
#include <vulkan/vulkan.h>

namespace lc::vk {

struct ImageTransition {
    VkImage image = VK_NULL_HANDLE;
    VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout new_layout = VK_IMAGE_LAYOUT_GENERAL;
    VkPipelineStageFlags2 src_stage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkAccessFlags2 src_access = 0;
    VkPipelineStageFlags2 dst_stage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkAccessFlags2 dst_access = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
};

void transition_image(VkCommandBuffer cmd, const ImageTransition& t);

// Makes earlier writes in src_stage visible to later accesses in dst_stage.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

}  // namespace lc::vk
