#pragma once
// Lightcuts by reconstruction cuts (Walter et al. 2005, Sec. 7) on the GPU:
// the bound criterion's full lightcut, shadow rays and all, at the corners of
// every block of RenderSettings::reconstruction_block pixels, each sample's
// cut kept as records (lightcuts_reconstruction_samples.comp); then every
// other pixel walks the tree along its corners' cuts and traces a shadow ray
// only where their visibility of a cluster disagrees, or runs a lightcut of
// its own where the corners differ from it in normal, depth or material
// (lightcuts_reconstruction_pixels.comp). Owns its records' set and pipelines.
#include <vulkan/vulkan.h>

#include <array>
#include <memory>

#include "editor_client/render/passes/frame_pass.h"
#include "editor_client/render/passes/reconstruction_records.h"
#include "editor_client/vk/pipeline_layout.h"
#include "editor_client/vk/specialization.h"

namespace lc::client {

class ReconstructionPass final : public FramePass {
public:
    // `frame_layout` is the frame's set 0, bound beside the records' set 1.
    static Result<std::unique_ptr<ReconstructionPass>> create(const vk::Device& device,
                                                              VkDescriptorSetLayout frame_layout);

    Status prepare(PipelineCache& pipelines, const Frame& frame) override;
    void record(VkCommandBuffer cmd, const Frame& frame) const override;
    VkPipelineStageFlags2 last_stage() const override;

private:
    enum Stage { kSamples = 0, kPixels = 1, kStageCount = 2 };

    ReconstructionPass(ReconstructionRecords records, vk::PipelineLayout layout)
        : records_(std::move(records)), layout_(std::move(layout)) {}
    vk::Specialization specialization(const Frame& frame) const;
    // The walk search's dispatches of one stage, over the samples or the pixels.
    void dispatch_stage(VkCommandBuffer cmd, const Frame& frame, Stage stage) const;

    ReconstructionRecords records_;
    vk::PipelineLayout layout_;
    std::array<VkPipeline, kStageCount> pipelines_{};
};

}  // namespace lc::client
