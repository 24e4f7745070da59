#pragma once
// A graphics pipeline for dynamic rendering (no render pass objects): vertex
// and fragment SPIR-V, vertex layout, attachment formats, dynamic viewport.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <vector>

#include "editor_client/vk/device_handle.h"
#include "editor_client/vk/specialization.h"
#include "lightcuts/result.h"

namespace lc::vk {

struct GraphicsPipelineDesc {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::span<const uint32_t> vertex_spirv;
    std::span<const uint32_t> fragment_spirv;
    Specialization* fragment_specialization = nullptr;
    std::vector<VkVertexInputBindingDescription> vertex_bindings;
    std::vector<VkVertexInputAttributeDescription> vertex_attributes;
    std::vector<VkFormat> color_formats;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
    VkCullModeFlags cull_mode = VK_CULL_MODE_NONE;
};

class GraphicsPipeline {
public:
    static Result<GraphicsPipeline> create(VkDevice device, const GraphicsPipelineDesc& desc);

    VkPipeline handle() const { return pipeline_.get(); }

private:
    DeviceHandle<VkPipeline> pipeline_;
};

}  // namespace lc::vk
