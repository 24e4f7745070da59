#pragma once
// The real-time mode's light-draw records on the GPU (set kDrawPairSet of
// RealtimePass's layout): one GpuDrawPair per tree node (lightcuts/tree/draw_pairs.h),
// remade whenever the renderer uploads a tree.
#include <vulkan/vulkan.h>

#include <span>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/command_pool.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/device.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/result.h"

namespace lc::client {

class DrawPairSet {
public:
    static Result<DrawPairSet> create(const vk::Device& device);

    // The records of `nodes` (make_walk_tree's; empty: no tree). The caller has
    // waited for the frames that read the old ones.
    Status upload(const vk::CommandPool& pool, std::span<const GpuTreeNode> nodes);

    VkDescriptorSetLayout set_layout() const { return set_layout_.handle(); }
    VkDescriptorSet descriptor_set() const { return set_; }

private:
    explicit DrawPairSet(const vk::Device& device) : device_(&device) {}

    const vk::Device* device_;
    vk::DescriptorSetLayout set_layout_;
    vk::DescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    vk::Buffer pairs_;
};

}  // namespace lc::client
