#include "editor_client/vk/graphics_pipeline.h"

#include <array>
#include <vector>

#include "editor_client/vk/shader_module.h"
#include "editor_client/vk/vk_result.h"

namespace lc::vk {

namespace {

std::array<VkPipelineShaderStageCreateInfo, 2> shader_stages(const ShaderModule& vertex,
                                                             const ShaderModule& fragment,
                                                             const GraphicsPipelineDesc& desc) {
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vertex.handle();
    stages[0].pName = "main";
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment.handle();
    stages[1].pName = "main";
    if (desc.fragment_specialization != nullptr)
        stages[1].pSpecializationInfo = desc.fragment_specialization->info();
    return stages;
}

// A description's fixed-function state: the create-infos point into this
// object and into the description, so it is made in place and never moved.
struct FixedFunctionState {
    explicit FixedFunctionState(const GraphicsPipelineDesc& desc) {
        vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(desc.vertex_bindings.size());
        vertex_input.pVertexBindingDescriptions = desc.vertex_bindings.data();
        vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(desc.vertex_attributes.size());
        vertex_input.pVertexAttributeDescriptions = desc.vertex_attributes.data();
        input_assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = desc.cull_mode;
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        depth.depthTestEnable = desc.depth_format != VK_FORMAT_UNDEFINED;
        depth.depthWriteEnable = desc.depth_format != VK_FORMAT_UNDEFINED;
        depth.depthCompareOp = VK_COMPARE_OP_LESS;
        blend_attachments.resize(desc.color_formats.size());
        for (VkPipelineColorBlendAttachmentState& a : blend_attachments)
            a.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                               VK_COLOR_COMPONENT_A_BIT;
        blend.attachmentCount = static_cast<uint32_t>(blend_attachments.size());
        blend.pAttachments = blend_attachments.data();
        dynamic.dynamicStateCount = static_cast<uint32_t>(dynamic_states.size());
        dynamic.pDynamicStates = dynamic_states.data();
        rendering.colorAttachmentCount = static_cast<uint32_t>(desc.color_formats.size());
        rendering.pColorAttachmentFormats = desc.color_formats.data();
        rendering.depthAttachmentFormat = desc.depth_format;
    }
    FixedFunctionState(const FixedFunctionState&) = delete;
    FixedFunctionState& operator=(const FixedFunctionState&) = delete;

    void attach_to(VkGraphicsPipelineCreateInfo& info) const {
        info.pNext = &rendering;
        info.pVertexInputState = &vertex_input;
        info.pInputAssemblyState = &input_assembly;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depth;
        info.pColorBlendState = &blend;
        info.pDynamicState = &dynamic;
    }

    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo input_assembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    std::vector<VkPipelineColorBlendAttachmentState> blend_attachments;
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    std::array<VkDynamicState, 2> dynamic_states{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
};

}  // namespace

Result<GraphicsPipeline> GraphicsPipeline::create(VkDevice device,
                                                  const GraphicsPipelineDesc& desc) {
    Result<ShaderModule> vertex = ShaderModule::create(device, desc.vertex_spirv);
    if (!vertex) return make_error("vertex shader: " + vertex.error());
    Result<ShaderModule> fragment = ShaderModule::create(device, desc.fragment_spirv);
    if (!fragment) return make_error("fragment shader: " + fragment.error());
    const std::array<VkPipelineShaderStageCreateInfo, 2> stages = shader_stages(*vertex, *fragment, desc);
    const FixedFunctionState state(desc);

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    state.attach_to(info);
    info.stageCount = static_cast<uint32_t>(stages.size());
    info.pStages = stages.data();
    info.layout = desc.layout;
    VkPipeline handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &handle));
    GraphicsPipeline pipeline;
    pipeline.pipeline_ = DeviceHandle<VkPipeline>(device, handle, vkDestroyPipeline);
    return pipeline;
}

}  // namespace lc::vk
