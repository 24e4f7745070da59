#pragma once
// The ReSTIR DI mode's lighting (RenderMode::kRestir, Bitterli et al. 2020),
// four dispatches that own their pipelines, reservoirs and descriptor sets:
// initial candidates drawn from the light tree and resampled, merged with the
// previous frame's reservoir (restir_candidates.comp); spatial reuse over
// neighbours, one shadow ray for the survivor and its shading
// (restir_spatial.comp); and the real-time mode's temporal pass
// (temporal_accumulate.comp: the running mean of a still view's frames, a
// short clamped history while it moves) and its edge-aware filter
// (spatial_filter.comp: fades out over the first frames, then copies the
// mean into the HDR image). The output pass tone-maps what it leaves there.
#include <vulkan/vulkan.h>

#include <array>
#include <memory>

#include "editor_client/render/passes/draw_pair_set.h"
#include "editor_client/render/passes/frame_pass.h"
#include "editor_client/render/passes/restir_reservoirs.h"
#include "editor_client/render/passes/temporal_history.h"
#include "editor_client/vk/pipeline_layout.h"

namespace lc::client {

class RestirPass final : public FramePass {
public:
    // `frame_layout` is the frame's set 0, bound beside the pass's own sets 1
    // (the temporal history), 2 (the light-draw records) and 3 (the reservoirs).
    static Result<std::unique_ptr<RestirPass>> create(const vk::Device& device,
                                                      VkDescriptorSetLayout frame_layout);

    Status prepare(PipelineCache& pipelines, const Frame& frame) override;
    void record(VkCommandBuffer cmd, const Frame& frame) const override;
    VkPipelineStageFlags2 last_stage() const override;

    // After the frame was recorded: its reservoirs and image become the next
    // frame's history.
    void advance();
    // The next frame starts anew (the tree or the lights changed).
    void drop_history() { history_.drop(); }
    // Frames in the still view's running mean after the last recorded frame.
    uint32_t frames_accumulated() const { return history_.frames_accumulated(); }
    void set_policy(const TemporalPolicy& policy) { history_.set_policy(policy); }
    // The light-draw records of a new tree (its compact nodes; empty: none).
    Status set_tree_nodes(const vk::CommandPool& pool, std::span<const GpuTreeNode> nodes) {
        return draws_.upload(pool, nodes);
    }

private:
    enum Stage { kCandidates = 0, kSpatial = 1, kTemporal = 2, kFilter = 3, kStageCount = 4 };

    RestirPass(TemporalHistory history, DrawPairSet draws, RestirReservoirs reservoirs, vk::PipelineLayout layout)
        : history_(std::move(history)),
          draws_(std::move(draws)),
          reservoirs_(std::move(reservoirs)),
          layout_(std::move(layout)) {}
    void dispatch(VkCommandBuffer cmd, const Frame& frame, Stage stage) const;

    TemporalHistory history_;
    DrawPairSet draws_;
    RestirReservoirs reservoirs_;
    vk::PipelineLayout layout_;
    std::array<VkPipeline, kStageCount> pipelines_{};
    uint32_t frames_recorded_ = 0;  // every frame's draws are seeded by its number
};

}  // namespace lc::client
