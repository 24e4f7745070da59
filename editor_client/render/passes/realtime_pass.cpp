#include "editor_client/render/passes/realtime_pass.h"

#include <string>

#include "editor_client/render/passes/compute_pass.h"
#include "editor_client/render/passes/lighting_pass.h"
#include "editor_client/vk/barriers.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/limits.h"
#include "lightcuts/device/pixel_representative.glsl.h"
#include "lightcuts/device/spec_constants.h"
#include "lightcuts/status_macros.h"
#include "spatial_filter_comp.spv.h"
#include "realtime_lighting_comp.spv.h"
#include "temporal_accumulate_comp.spv.h"

namespace lc::client {

Result<std::unique_ptr<RealtimePass>> RealtimePass::create(const vk::Device& device,
                                                           VkDescriptorSetLayout frame_layout) {
    Result<TemporalHistory> history = TemporalHistory::create(device);
    if (!history) return make_error(history.error());
    Result<DrawPairSet> draws = DrawPairSet::create(device);
    if (!draws) return make_error(draws.error());
    static_assert(kTemporalSet == 1u && kDrawPairSet == 2u);
    std::array<VkDescriptorSetLayout, 3> sets{frame_layout, history->set_layout(), draws->set_layout()};
    VkPushConstantRange constants{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GpuFrameConstants)};
    Result<vk::PipelineLayout> layout =
        vk::PipelineLayout::create(device.handle(), sets, std::span(&constants, 1));
    if (!layout) return make_error(layout.error());
    return std::unique_ptr<RealtimePass>(
        new RealtimePass(std::move(history).value(), std::move(draws).value(), std::move(layout).value()));
}

Status RealtimePass::prepare(PipelineCache& pipelines, const Frame& frame) {
    if (frame.workgroup_size * frame.workgroup_size > kMaxWorkgroupInvocations)
        return make_error("the real-time mode needs workgroups of at most " +
                          std::to_string(kMaxWorkgroupInvocations) + " pixels");
    LC_RETURN_IF_ERROR(history_.prepare(*frame.settings));
    const std::array<std::span<const uint32_t>, kStageCount> modules{
        spirv_words(realtime_lighting_comp_spv), spirv_words(temporal_accumulate_comp_spv),
        spirv_words(spatial_filter_comp_spv)};
    for (int stage = 0; stage < kStageCount; ++stage) {
        vk::Specialization spec;
        spec.set_uint(kSpecWorkgroupX, frame.workgroup_size)
            .set_uint(kSpecWorkgroupY, frame.workgroup_size);
        if (stage == kLighting) {
            specialize_lighting(spec, frame);
            // Its cut nodes are evaluated through its own draws (stochastic_draw.glsl),
            // not a representative: one pipeline whatever --representatives says.
            spec.set_uint(kSpecRepresentatives, device::kRepresentativesTree)
                .set_uint(kSpecStochasticCut, frame.settings->realtime_cut)
                .set_uint(kSpecStochasticRays, frame.settings->realtime_rays);
        }
        Result<VkPipeline> pipeline = pipelines.compute(layout_.handle(), modules[stage], spec);
        if (!pipeline) return make_error("real-time pipeline: " + pipeline.error());
        pipelines_[stage] = *pipeline;
    }
    return Ok{};
}

void RealtimePass::dispatch(VkCommandBuffer cmd, const Frame& frame, Stage stage) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[stage]);
    GpuFrameConstants constants = frame.constants;
    // Draws differ per frame and per seed (render --representative-seed).
    constants.frame_seed = frames_recorded_ * 0x9E3779B9u + frame.settings->representative_seed;
    // Spread: the frames step along each pixel's sequences. Independent: every
    // frame starts its sequences from offsets of its own (frame 0 of a new seed).
    const bool spread = history_.policy().spread_frames;
    constants.frame_number = spread ? frames_recorded_ : 0u;
    constants.draw_seed = spread ? frame.settings->representative_seed : constants.frame_seed;
    vkCmdPushConstants(cmd, layout_.handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants),
                       &constants);
    const uint32_t size = frame.workgroup_size;
    for (const PixelRegion& r : frame.regions)
        vkCmdDispatchBase(cmd, r.x / size, r.y / size, 0, (r.width + size - 1) / size,
                          (r.height + size - 1) / size, 1);
}

void RealtimePass::record(VkCommandBuffer cmd, const Frame& frame) const {
    begin_lighting_images(cmd, frame);
    history_.record_setup(cmd);
    const std::array<VkDescriptorSet, 3> sets{frame.frame_set, history_.descriptor_set(),
                                              draws_.descriptor_set()};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.handle(), 0,
                            uint32_t(sets.size()), sets.data(), 0, nullptr);
    for (int stage = 0; stage < kStageCount; ++stage) {
        // Each stage reads what the one before wrote, around its pixel.
        if (stage > 0)
            vk::memory_barrier(cmd, kComputeStage, kStorageWrite, kComputeStage, kStorageReadWrite);
        dispatch(cmd, frame, Stage(stage));
    }
}

VkPipelineStageFlags2 RealtimePass::last_stage() const { return kComputeStage; }

void RealtimePass::advance() {
    history_.advance();
    ++frames_recorded_;
}

}  // namespace lc::client
