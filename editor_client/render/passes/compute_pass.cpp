#include "editor_client/render/passes/compute_pass.h"

#include <string>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"

namespace lc::client {

vk::Specialization ComputePass::specialization(const Frame& frame) const {
    vk::Specialization spec;
    spec.set_uint(kSpecWorkgroupX, frame.workgroup_size)
        .set_uint(kSpecWorkgroupY, frame.workgroup_size);
    specialize(spec, frame);
    return spec;
}

Result<VkPipeline> ComputePass::create_pipeline(PipelineCache& pipelines, const Frame& frame) {
    vk::Specialization spec = specialization(frame);
    return pipelines.compute(frame.compute_layout, module(frame), spec);
}

Status ComputePass::prepare(PipelineCache& pipelines, const Frame& frame) {
    Result<VkPipeline> pipeline = create_pipeline(pipelines, frame);
    if (!pipeline) return make_error(std::string(role()) + " pipeline: " + pipeline.error());
    pipeline_ = *pipeline;
    return Ok{};
}

void ComputePass::bind(VkCommandBuffer cmd, const Frame& frame) const {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, frame.compute_layout, 0, 1,
                            &frame.frame_set, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
}

void ComputePass::dispatch(VkCommandBuffer cmd, const Frame& frame,
                           const GpuFrameConstants& constants) {
    vkCmdPushConstants(cmd, frame.compute_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants),
                       &constants);
    const uint32_t size = frame.workgroup_size;
    for (const PixelRegion& r : frame.regions)
        vkCmdDispatchBase(cmd, r.x / size, r.y / size, 0, (r.width + size - 1) / size,
                          (r.height + size - 1) / size, 1);
}

}  // namespace lc::client
