#pragma once
// A pass of compute dispatches over the image, one invocation per pixel, with
// the frame's descriptor set and push constants. Subclasses name the SPIR-V
// module and its specialization constants.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

#include "editor_client/render/passes/frame_pass.h"
#include "editor_client/vk/specialization.h"

namespace lc::client {

// Pipeline stage and accesses of the compute passes' barriers.
inline constexpr VkPipelineStageFlags2 kComputeStage = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
inline constexpr VkAccessFlags2 kStorageWrite = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
inline constexpr VkAccessFlags2 kStorageReadWrite =
    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

class ComputePass : public FramePass {
public:
    Status prepare(PipelineCache& pipelines, const Frame& frame) final;
    VkPipelineStageFlags2 last_stage() const final { return kComputeStage; }

protected:
    // What the pipeline is for, in a creation error ("lighting", "output").
    virtual const char* role() const = 0;
    virtual std::span<const uint32_t> module(const Frame& frame) const = 0;
    // Adds this pass's constants to the workgroup size already set.
    virtual void specialize(vk::Specialization& spec, const Frame& frame) const = 0;
    // The workgroup size and specialize()'s constants.
    vk::Specialization specialization(const Frame& frame) const;
    // The pipeline of specialization(frame); a pass whose constants the
    // driver may refuse (BoundHeapPass) tries others.
    virtual Result<VkPipeline> create_pipeline(PipelineCache& pipelines, const Frame& frame);

    // Binds the frame's set and this pass's pipeline.
    void bind(VkCommandBuffer cmd, const Frame& frame) const;
    // One dispatch over each of the frame's regions with these push constants.
    static void dispatch(VkCommandBuffer cmd, const Frame& frame, const GpuFrameConstants& constants);

private:
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

template <size_t N>
std::span<const uint32_t> spirv_words(const uint32_t (&words)[N]) {
    return std::span<const uint32_t>(words, N);
}

}  // namespace lc::client
