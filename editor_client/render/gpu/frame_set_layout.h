#pragma once
// The layout of the compute passes' descriptor set (lightcuts/device/bindings.h's
// bindings): storage images for the G-buffer and outputs, then storage buffers.
#include <vulkan/vulkan.h>

#include "editor_client/vk/descriptor_set.h"
#include "lightcuts/result.h"

namespace lc::client {

Result<vk::DescriptorSetLayout> create_frame_set_layout(VkDevice device);

}  // namespace lc::client
