#include "editor_client/render/frame_set_layout.h"

#include <array>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"

namespace lc::client {

Result<vk::DescriptorSetLayout> create_frame_set_layout(VkDevice device) {
    std::array<VkDescriptorSetLayoutBinding, kFrameBindingCount> bindings{};
    for (uint32_t b = 0; b < kFrameBindingCount; ++b) {
        bindings[b].binding = b;
        bindings[b].descriptorType = b < kBindLeafLights ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                                         : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[b].descriptorCount = 1;
        bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    return vk::DescriptorSetLayout::create(device, bindings);
}

}  // namespace lc::client
