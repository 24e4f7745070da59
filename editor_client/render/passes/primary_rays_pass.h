#pragma once
// The G-buffer by rays (RenderSettings::primary = kRays, shaders/primary_rays.comp):
// a compute pass that writes what GBufferPass rasterises, from a BVH over
// every triangle of the scene, built on first use and owned here with its
// buffers and descriptor set (set kPrimarySet beside the frame's set 0).
// Compute GPUs rasterise on few units (an H200: 6.1 ms for a 1080p G-buffer
// of a few hundred triangles); every unit casts rays. A scene with textured
// or alpha-masked materials stays on raster (primary_rays_unsupported).
#include <vulkan/vulkan.h>

#include <memory>
#include <optional>
#include <string>

#include "editor_client/render/gpu/gpu_scene.h"
#include "editor_client/render/passes/frame_pass.h"
#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/pipeline_layout.h"
#include "lightcuts/scene.h"

namespace lc::client {

class PrimaryRaysPass final : public FramePass {
public:
    // All three must outlive the pass.
    static Result<std::unique_ptr<PrimaryRaysPass>> create(const vk::Context& context,
                                                           VkDescriptorSetLayout frame_layout,
                                                           const GpuScene& gpu_scene, const Scene& scene);

    Status prepare(PipelineCache& pipelines, const Frame& frame) override;
    void record(VkCommandBuffer cmd, const Frame& frame) const override;
    VkPipelineStageFlags2 last_stage() const override;

    // BVH nodes over the scene's triangles (0 before the first frame by rays).
    uint32_t node_count() const { return node_count_; }
    // Why this scene's G-buffer cannot be cast as rays (primary_rays_unsupported), empty when it can.
    const std::string& unsupported() const { return unsupported_; }

private:
    PrimaryRaysPass(const vk::Context& context, const GpuScene& gpu_scene, const Scene& scene);
    Status build_geometry();
    Status upload(vk::Buffer& out, std::span<const std::byte> bytes);

    const vk::Context& context_;
    const GpuScene& gpu_scene_;
    const Scene& scene_;
    vk::DescriptorSetLayout set_layout_;
    vk::DescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    vk::PipelineLayout layout_;
    vk::Buffer nodes_, triangles_, sources_, materials_, params_buffer_;
    std::string unsupported_;  // the scene's materials decide it once
    bool built_ = false;
    uint32_t node_count_ = 0;
    GpuPrimaryParams params_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace lc::client
