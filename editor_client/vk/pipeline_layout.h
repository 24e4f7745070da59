#pragma once
// Descriptor set layouts and push-constant ranges a pipeline is built against.
#include <vulkan/vulkan.h>

#include <span>

#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

class PipelineLayout {
public:
    static Result<PipelineLayout> create(VkDevice device,
                                         std::span<const VkDescriptorSetLayout> set_layouts,
                                         std::span<const VkPushConstantRange> push_constants);

    VkPipelineLayout handle() const { return layout_.get(); }

private:
    DeviceHandle<VkPipelineLayout> layout_;
};

}  // namespace lc::vk
