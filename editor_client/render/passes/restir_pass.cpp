#include "editor_client/render/passes/restir_pass.h"

#include <string>

#include "editor_client/render/passes/compute_pass.h"
#include "editor_client/render/passes/lighting_pass.h"
#include "editor_client/vk/barriers.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/limits.h"
#include "lightcuts/device/pixel_representative.glsl.h"
#include "lightcuts/device/restir.h"
#include "lightcuts/device/spec_constants.h"
#include "lightcuts/status_macros.h"
#include "restir_candidates_comp.spv.h"
#include "restir_spatial_comp.spv.h"
#include "spatial_filter_comp.spv.h"
#include "temporal_accumulate_comp.spv.h"

namespace lc::client {
namespace {

void specialize_restir(vk::Specialization& spec, const RestirSettings& restir) {
    spec.set_uint(kSpecRestirCandidates, restir.candidates)
        .set_uint(kSpecRestirSource, restir.source == RestirSource::kPower ? kRestirSourcePower : kRestirSourceTree)
        .set_uint(kSpecRestirSpatial, restir.spatial)
        .set_bool(kSpecRestirTemporal, restir.temporal)
        .set_bool(kSpecRestirUnbiased, restir.bias == RestirBias::kUnbiased)
        .set_bool(kSpecRestirCandidateVisibility, restir.candidate_visibility);
}

}  // namespace

Result<std::unique_ptr<RestirPass>> RestirPass::create(const vk::Device& device,
                                                       VkDescriptorSetLayout frame_layout) {
    Result<TemporalHistory> history = TemporalHistory::create(device);
    if (!history) return make_error(history.error());
    Result<DrawPairSet> draws = DrawPairSet::create(device);
    if (!draws) return make_error(draws.error());
    Result<RestirReservoirs> reservoirs = RestirReservoirs::create(device);
    if (!reservoirs) return make_error(reservoirs.error());
    static_assert(kTemporalSet == 1u && kDrawPairSet == 2u && kRestirSet == 3u);
    std::array<VkDescriptorSetLayout, 4> sets{frame_layout, history->set_layout(), draws->set_layout(),
                                              reservoirs->set_layout()};
    VkPushConstantRange constants{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GpuFrameConstants)};
    Result<vk::PipelineLayout> layout =
        vk::PipelineLayout::create(device.handle(), sets, std::span(&constants, 1));
    if (!layout) return make_error(layout.error());
    return std::unique_ptr<RestirPass>(new RestirPass(std::move(history).value(), std::move(draws).value(),
                                                      std::move(reservoirs).value(), std::move(layout).value()));
}

Status RestirPass::prepare(PipelineCache& pipelines, const Frame& frame) {
    LC_RETURN_IF_ERROR(history_.prepare(*frame.settings));
    LC_RETURN_IF_ERROR(reservoirs_.prepare(frame.settings->width, frame.settings->height));
    const std::array<std::span<const uint32_t>, kStageCount> modules{
        spirv_words(restir_candidates_comp_spv), spirv_words(restir_spatial_comp_spv),
        spirv_words(temporal_accumulate_comp_spv), spirv_words(spatial_filter_comp_spv)};
    for (int stage = 0; stage < kStageCount; ++stage) {
        vk::Specialization spec;
        spec.set_uint(kSpecWorkgroupX, frame.workgroup_size).set_uint(kSpecWorkgroupY, frame.workgroup_size);
        if (stage == kCandidates || stage == kSpatial) {
            specialize_lighting(spec, frame);
            spec.set_uint(kSpecRepresentatives, device::kRepresentativesTree);
            specialize_restir(spec, frame.settings->restir);
        }
        Result<VkPipeline> pipeline = pipelines.compute(layout_.handle(), modules[stage], spec);
        if (!pipeline) return make_error("ReSTIR pipeline: " + pipeline.error());
        pipelines_[stage] = *pipeline;
    }
    return Ok{};
}

void RestirPass::dispatch(VkCommandBuffer cmd, const Frame& frame, Stage stage) const {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[stage]);
    GpuFrameConstants constants = frame.constants;
    // Candidates and neighbours differ per frame and per seed (render --representative-seed).
    constants.frame_seed = frames_recorded_ * 0x9E3779B9u + frame.settings->representative_seed;
    constants.frame_number = frames_recorded_;
    constants.draw_seed = frame.settings->representative_seed;
    vkCmdPushConstants(cmd, layout_.handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
    const uint32_t size = frame.workgroup_size;
    for (const PixelRegion& r : frame.regions)
        vkCmdDispatchBase(cmd, r.x / size, r.y / size, 0, (r.width + size - 1) / size,
                          (r.height + size - 1) / size, 1);
}

void RestirPass::record(VkCommandBuffer cmd, const Frame& frame) const {
    begin_lighting_images(cmd, frame);
    history_.record_setup(cmd);
    const std::array<VkDescriptorSet, 4> sets{frame.frame_set, history_.descriptor_set(), draws_.descriptor_set(),
                                              reservoirs_.descriptor_set()};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.handle(), 0, uint32_t(sets.size()),
                            sets.data(), 0, nullptr);
    for (int stage = 0; stage < kStageCount; ++stage) {
        // Each stage reads what the one before wrote, around its pixel.
        if (stage > 0) vk::memory_barrier(cmd, kComputeStage, kStorageWrite, kComputeStage, kStorageReadWrite);
        dispatch(cmd, frame, Stage(stage));
    }
}

VkPipelineStageFlags2 RestirPass::last_stage() const { return kComputeStage; }

void RestirPass::advance() {
    history_.advance();
    reservoirs_.advance();
    ++frames_recorded_;
}

}  // namespace lc::client
