#include "editor_client/vk/compute_pipeline.h"

#include "editor_client/vk/shader_module.h"
#include "editor_client/vk/vk_result.h"

namespace lc::vk {

Result<ComputePipeline> ComputePipeline::create(VkDevice device, VkPipelineLayout layout,
                                                std::span<const uint32_t> spirv,
                                                Specialization& specialization) {
    Result<ShaderModule> module = ShaderModule::create(device, spirv);
    if (!module) return make_error(module.error());
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module->handle();
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = specialization.info();
    info.layout = layout;
    // Dispatches may start at a workgroup offset (the renderer's pixel regions).
    info.flags = VK_PIPELINE_CREATE_DISPATCH_BASE_BIT;
    VkPipeline handle = VK_NULL_HANDLE;
    LC_VK_CHECK(vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &handle));
    ComputePipeline pipeline;
    pipeline.pipeline_ = DeviceHandle<VkPipeline>(device, handle, vkDestroyPipeline);
    return pipeline;
}

}  // namespace lc::vk
