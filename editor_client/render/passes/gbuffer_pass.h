#pragma once
// The G-buffer pass: the scene's triangles rasterised into position, normal,
// albedo and emissive attachments, which end in VK_IMAGE_LAYOUT_GENERAL for
// the compute passes.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <memory>

#include "editor_client/render/gpu/gpu_scene.h"
#include "editor_client/render/passes/frame_pass.h"
#include "editor_client/vk/pipeline_layout.h"
#include "lightcuts/scene.h"

namespace lc::client {

class GBufferPass final : public FramePass {
public:
    // Both must outlive the pass.
    static Result<std::unique_ptr<GBufferPass>> create(VkDevice device, const GpuScene& gpu_scene,
                                                       const Scene& scene);

    Status prepare(PipelineCache& pipelines, const Frame& frame) override;
    void record(VkCommandBuffer cmd, const Frame& frame) const override;
    VkPipelineStageFlags2 last_stage() const override {
        return VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    }

private:
    GBufferPass(const GpuScene& gpu_scene, const Scene& scene, vk::PipelineLayout layout);
    void draw(VkCommandBuffer cmd, const Frame& frame) const;

    const GpuScene& gpu_scene_;
    const Scene& scene_;
    vk::PipelineLayout layout_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// Projection * view for a camera (Vulkan clip space: y down, depth 0..1), with
// near and far planes that enclose the scene bounds.
glm::mat4 view_projection(const RenderCamera& camera, float aspect, const glm::vec3& bounds_min,
                          const glm::vec3& bounds_max);
// The frame's view_projection with its eye rays placed as `settings` asks
// (RenderSettings::pixel_offset, corner_grid), for a width x height frame.
glm::mat4 eye_ray_view_projection(const RenderSettings& settings, uint32_t width,
                                   uint32_t height, const glm::vec3& bounds_min,
                                   const glm::vec3& bounds_max);

}  // namespace lc::client
