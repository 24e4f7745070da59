#pragma once
// A compute pipeline from one SPIR-V module and its specialization constants.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

#include "editor_client/vk/device_handle.h"
#include "editor_client/vk/specialization.h"
#include "lightcuts/result.h"

namespace lc::vk {

class ComputePipeline {
public:
    static Result<ComputePipeline> create(VkDevice device, VkPipelineLayout layout,
                                          std::span<const uint32_t> spirv,
                                          Specialization& specialization);

    VkPipeline handle() const { return pipeline_.get(); }

private:
    DeviceHandle<VkPipeline> pipeline_;
};

}  // namespace lc::vk
