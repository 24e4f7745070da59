#pragma once
// A texture sampler (linear filtering, repeat addressing: glTF's defaults).
#include <vulkan/vulkan.h>

#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

class Sampler {
public:
    static Result<Sampler> create_linear_repeat(VkDevice device);

    VkSampler handle() const { return sampler_.get(); }

private:
    DeviceHandle<VkSampler> sampler_;
};

}  // namespace lc::vk
