#pragma once
// A pass of a frame (G-buffer, lighting, output) and what it records with.
// The renderer owns the frame's resources (targets, buffers, the descriptor
// set, timestamps); a pass finds its pipelines before recording and then
// records its commands between the renderer's timestamps.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>

#include "editor_client/render/gpu/pipeline_cache.h"
#include "editor_client/render/gpu/pixel_region.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/gpu/render_targets.h"
#include "editor_client/render/analysis/scene_effects.h"
#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/result.h"

namespace lc::client {

// A run of a pass's dispatches, by their index in the pass's sequence.
struct DispatchRange {
    uint32_t begin = 0;
    uint32_t end = UINT32_MAX;

    bool contains(uint32_t index) const { return index >= begin && index < end; }
};

struct Frame {
    const RenderSettings* settings = nullptr;
    const RenderTargets* targets = nullptr;
    const SceneEffects* effects = nullptr;
    bool shadows = false;  // shadow rays are traced (asked for, and something occludes)
    bool alpha_masks = false;  // of the occluders, some are alpha-masked (kSpecAlphaMasks)
    uint32_t workgroup_size = 8;
    VkPipelineLayout compute_layout = VK_NULL_HANDLE;
    VkDescriptorSet frame_set = VK_NULL_HANDLE;
    GpuFrameConstants constants;  // what every compute dispatch pushes, before a pass adjusts it
    uint32_t reference_chunk = 1;  // leaves per reference dispatch (the device's loop limit)
    // The pixels the compute passes shade (the whole image, or tiles of it),
    // their origins on workgroup boundaries.
    std::span<const PixelRegion> regions;
    // The lighting and output images keep what earlier regions wrote (the
    // G-buffer is not redrawn); otherwise the frame starts a new image.
    bool continues_image = false;
    // The reference's dispatches this recording makes: a long reference is
    // split over several submissions (Renderer::render), each a run of them.
    DispatchRange reference_dispatches;
};

class FramePass {
public:
    virtual ~FramePass() = default;

    // Finds or builds the pipelines `frame` needs; called before anything is
    // recorded, so that a failure leaves the command buffer as it was.
    virtual Status prepare(PipelineCache& pipelines, const Frame& frame) = 0;
    // Records the pass with the pipelines prepare() found for the same frame.
    virtual void record(VkCommandBuffer cmd, const Frame& frame) const = 0;
    // The stage whose completion ends the pass (its end timestamp).
    virtual VkPipelineStageFlags2 last_stage() const = 0;
};

}  // namespace lc::client
