#include "editor_client/vk/pipeline_layout.h"

#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<PipelineLayout> PipelineLayout::create(VkDevice device,
                                              std::span<const VkDescriptorSetLayout> set_layouts,
                                              std::span<const VkPushConstantRange> push_constants) {
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = static_cast<uint32_t>(set_layouts.size());
    info.pSetLayouts = set_layouts.data();
    info.pushConstantRangeCount = static_cast<uint32_t>(push_constants.size());
    info.pPushConstantRanges = push_constants.data();
    VkPipelineLayout handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &handle));
    PipelineLayout layout;
    layout.layout_ = DeviceHandle<VkPipelineLayout>(device, handle, vkDestroyPipelineLayout);
    return layout;
}

}  // namespace lc::vk
