#pragma once
// A SPIR-V shader module (the words come from the headers shaders/ generates).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

class ShaderModule {
public:
    static Result<ShaderModule> create(VkDevice device, std::span<const uint32_t> spirv);

    VkShaderModule handle() const { return module_.get(); }

private:
    DeviceHandle<VkShaderModule> module_;
};

}  // namespace lc::vk
