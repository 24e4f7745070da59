#pragma once
// The real-time mode's lighting (RenderMode::kRealtime), three dispatches
// that own their pipelines, history and descriptor set: stochastic lightcuts
// (realtime_lighting.comp: one cut per block refined at a pivot drawn each
// frame, one light drawn in each cut node per pixel, one shadow ray each),
// temporal accumulation (temporal_accumulate.comp: a running mean while the
// view rests, a reprojected and clamped short history while it moves) and an
// edge-aware spatial filter that fades out as the history grows
// (spatial_filter.comp). The output pass tone-maps what it leaves in the HDR image.
#include <vulkan/vulkan.h>

#include <array>
#include <memory>

#include "editor_client/render/passes/draw_pair_set.h"
#include "editor_client/render/passes/frame_pass.h"
#include "editor_client/render/passes/temporal_history.h"
#include "editor_client/vk/pipeline_layout.h"

namespace lc::client {

class RealtimePass final : public FramePass {
public:
    // `frame_layout` is the frame's set 0, bound beside the pass's own sets 1
    // (the history) and 2 (the light-draw records).
    static Result<std::unique_ptr<RealtimePass>> create(const vk::Device& device,
                                                        VkDescriptorSetLayout frame_layout);

    Status prepare(PipelineCache& pipelines, const Frame& frame) override;
    void record(VkCommandBuffer cmd, const Frame& frame) const override;
    VkPipelineStageFlags2 last_stage() const override;

    // After the frame was recorded: it becomes the history of the next one,
    // whose lights are drawn anew.
    void advance();
    // The next frame starts a new history (the tree or the lights changed).
    void drop_history() { history_.drop(); }
    // Frames in the history after the last recorded frame (1: a new start).
    uint32_t frames_accumulated() const { return history_.frames_accumulated(); }
    void set_policy(const TemporalPolicy& policy) { history_.set_policy(policy); }
    // The light-draw records of a new tree (its compact nodes; empty: none).
    Status set_tree_nodes(const vk::CommandPool& pool, std::span<const GpuTreeNode> nodes) {
        return draws_.upload(pool, nodes);
    }

private:
    enum Stage { kLighting = 0, kTemporal = 1, kFilter = 2, kStageCount = 3 };

    RealtimePass(TemporalHistory history, DrawPairSet draws, vk::PipelineLayout layout)
        : history_(std::move(history)), draws_(std::move(draws)), layout_(std::move(layout)) {}
    void dispatch(VkCommandBuffer cmd, const Frame& frame, Stage stage) const;

    TemporalHistory history_;
    DrawPairSet draws_;
    vk::PipelineLayout layout_;
    std::array<VkPipeline, kStageCount> pipelines_{};
    uint32_t frames_recorded_ = 0;  // every frame's draws are seeded by its number
};

}  // namespace lc::client
