#include "editor_client/render/passes/reconstruction_pass.h"

#include <array>
#include <bit>
#include <string>

#include "editor_client/render/passes/compute_pass.h"
#include "editor_client/render/passes/lighting_pass.h"
#include "editor_client/vk/barriers.h"
#include "lightcuts/cuts/bound_walk.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "lightcuts/status_macros.h"
#include "lightcuts_reconstruction_pixels_comp.spv.h"
#include "lightcuts_reconstruction_samples_comp.spv.h"

namespace lc::client {

Result<std::unique_ptr<ReconstructionPass>> ReconstructionPass::create(const vk::Device& device,
                                                                       VkDescriptorSetLayout frame_layout) {
    Result<ReconstructionRecords> records = ReconstructionRecords::create(device);
    if (!records) return make_error(records.error());
    static_assert(kReconstructionSet == 1u);
    std::array<VkDescriptorSetLayout, 2> sets{frame_layout, records->set_layout()};
    VkPushConstantRange constants{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GpuFrameConstants)};
    Result<vk::PipelineLayout> layout =
        vk::PipelineLayout::create(device.handle(), sets, std::span(&constants, 1));
    if (!layout) return make_error(layout.error());
    return std::unique_ptr<ReconstructionPass>(
        new ReconstructionPass(std::move(records).value(), std::move(layout).value()));
}

// Every lighting constant, the walk search's (as BoundWalkPass sets them, one
// cut per pixel: samples blocks apart share nothing) and the blocks'.
vk::Specialization ReconstructionPass::specialization(const Frame& frame) const {
    const RenderSettings& settings = *frame.settings;
    vk::Specialization spec;
    spec.set_uint(kSpecWorkgroupX, frame.workgroup_size).set_uint(kSpecWorkgroupY, frame.workgroup_size);
    specialize_lighting(spec, frame);
    spec.set_uint(kSpecRepresentatives, static_cast<uint32_t>(settings.representatives))
        .set_uint(kSpecRepresentativeSeed, settings.representative_seed)
        .set_uint(kSpecErrorRatio, std::bit_cast<uint32_t>(settings.error_ratio))
        .set_uint(kSpecWalkMaxCut, settings.max_cut)
        .set_uint(kSpecWalkMaxPasses, kWalkMaxPasses)
        .set_uint(kSpecWalkShrink, std::bit_cast<uint32_t>(kWalkShrink))
        .set_uint(kSpecWalkMargin, std::bit_cast<uint32_t>(kWalkMargin))
        .set_uint(kSpecWalkBisections, kWalkBisections)
        .set_bool(kSpecWalkShareCuts, false)
        .set_uint(kSpecReconstructionBlock, settings.reconstruction_block)
        .set_uint(kSpecReconstructionCap, settings.reconstruction_cap);
    return spec;
}

Status ReconstructionPass::prepare(PipelineCache& pipelines, const Frame& frame) {
    const RenderSettings& settings = *frame.settings;
    if (settings.reconstruction_block < 2)
        return make_error("reconstruction cuts need blocks of at least 2 pixels");
    LC_RETURN_IF_ERROR(records_.reserve(settings.width, settings.height, settings.reconstruction_block,
                                        settings.reconstruction_cap));
    const std::array<std::span<const uint32_t>, kStageCount> modules{
        spirv_words(lightcuts_reconstruction_samples_comp_spv),
        spirv_words(lightcuts_reconstruction_pixels_comp_spv)};
    vk::Specialization spec = specialization(frame);
    for (int stage = 0; stage < kStageCount; ++stage) {
        Result<VkPipeline> pipeline = pipelines.compute(layout_.handle(), modules[stage], spec);
        if (!pipeline) return make_error("reconstruction pipeline: " + pipeline.error());
        pipelines_[stage] = *pipeline;
    }
    return Ok{};
}

void ReconstructionPass::dispatch_stage(VkCommandBuffer cmd, const Frame& frame, Stage stage) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[stage]);
    const RenderSettings& settings = *frame.settings;
    const uint32_t size = frame.workgroup_size;
    const uint32_t lattice_x = reconstruction_lattice_side(settings.width, settings.reconstruction_block);
    const uint32_t lattice_y = reconstruction_lattice_side(settings.height, settings.reconstruction_block);
    // As BoundWalkPass: a pass the loop limit cuts short runs again in the
    // next dispatch, so kWalkMaxPasses of them end every search.
    GpuFrameConstants constants = frame.constants;
    for (uint32_t d = 0; d < kWalkMaxPasses; ++d) {
        constants.walk_dispatch = d;
        if (d > 0)
            vk::memory_barrier(cmd, kComputeStage, kStorageReadWrite, kComputeStage, kStorageReadWrite);
        vkCmdPushConstants(cmd, layout_.handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants),
                           &constants);
        if (stage == kSamples) {
            vkCmdDispatch(cmd, (lattice_x + size - 1) / size, (lattice_y + size - 1) / size, 1);
            continue;
        }
        for (const PixelRegion& r : frame.regions)
            vkCmdDispatchBase(cmd, r.x / size, r.y / size, 0, (r.width + size - 1) / size,
                              (r.height + size - 1) / size, 1);
    }
}

void ReconstructionPass::record(VkCommandBuffer cmd, const Frame& frame) const {
    begin_lighting_images(cmd, frame);
    const std::array<VkDescriptorSet, 2> sets{frame.frame_set, records_.descriptor_set()};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.handle(), 0, uint32_t(sets.size()),
                            sets.data(), 0, nullptr);
    dispatch_stage(cmd, frame, kSamples);
    // The pixels read every sample's records.
    vk::memory_barrier(cmd, kComputeStage, kStorageReadWrite, kComputeStage, kStorageReadWrite);
    dispatch_stage(cmd, frame, kPixels);
}

VkPipelineStageFlags2 ReconstructionPass::last_stage() const { return kComputeStage; }

}  // namespace lc::client
