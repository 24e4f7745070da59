#include "editor_client/render/gpu/frame_set_layout.h"

#include <array>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"

namespace lc::client {

Result<vk::DescriptorSetLayout> create_frame_set_layout(VkDevice device) {
    std::array<VkDescriptorType, kFrameBindingCount> types{};
    for (uint32_t b = 0; b < kFrameBindingCount; ++b)
        types[b] = b < kBindLeafLights ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return vk::DescriptorSetLayout::create(device, types, VK_SHADER_STAGE_COMPUTE_BIT);
}

}  // namespace lc::client
