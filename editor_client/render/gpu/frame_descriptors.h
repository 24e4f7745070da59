#pragma once
// The compute passes' set 0 (frame_set_layout.h): its pool and the one set,
// the pipeline layout with the frame's push constants, and whether the set
// must be written again (a buffer or a target was remade since).
#include <vulkan/vulkan.h>

#include "editor_client/render/gpu/background_buffers.h"
#include "editor_client/render/gpu/gpu_lights.h"
#include "editor_client/render/gpu/gpu_occluders.h"
#include "editor_client/render/gpu/render_targets.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/pipeline_layout.h"
#include "lightcuts/result.h"

namespace lc::client {

// The buffers of set 0 that are not the targets', lights', occluders' or background's.
struct FrameBuffers {
    VkBuffer counters = VK_NULL_HANDLE;        // GpuFrameCounters
    VkBuffer vpl_visibility = VK_NULL_HANDLE;  // GpuVisibilityBits
};

class FrameDescriptors {
public:
    Status create(VkDevice device);

    VkDescriptorSetLayout layout() const { return layout_.handle(); }
    VkPipelineLayout compute_layout() const { return compute_layout_.handle(); }
    VkDescriptorSet set() const { return set_; }
    void mark_dirty() { dirty_ = true; }
    // Writes every binding when something was remade since the last write.
    void update(VkDevice device, const RenderTargets& targets, const GpuLights& lights,
                const GpuOccluders& occluders, const BackgroundBuffers& background, const FrameBuffers& buffers);

private:
    vk::DescriptorSetLayout layout_;
    vk::DescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    bool dirty_ = true;
    vk::PipelineLayout compute_layout_;
};

}  // namespace lc::client
