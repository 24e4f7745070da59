#pragma once
// The lights a frame shades, on the GPU: the walk tree's leaves (or, without
// a tree, the scene's lights), its compact nodes and the classic lights
// (shaded one by one), with their counts.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc::client {

class GpuLights {
public:
    // Uploads the scene's lights and `tree` (null: none) as they are.
    Status upload(const vk::Context& context, const Scene& scene, const WalkTree* tree);

    bool has_tree() const { return has_tree_; }
    uint32_t leaf_count() const { return leaf_count_; }
    uint32_t classic_count() const { return classic_count_; }
    uint32_t node_count() const { return node_count_; }
    uint32_t tree_depth() const { return tree_depth_; }
    VkBuffer leaves() const { return leaves_.handle(); }
    VkBuffer nodes() const { return nodes_.handle(); }
    VkBuffer classic() const { return classic_.handle(); }

private:
    vk::Buffer leaves_;   // GpuLight: the tree's leaves in index order, or the scene's lights
    vk::Buffer nodes_;    // GpuTreeNode
    vk::Buffer classic_;  // GpuLight
    bool has_tree_ = false;
    uint32_t leaf_count_ = 0;
    uint32_t classic_count_ = 0;
    uint32_t node_count_ = 0;
    uint32_t tree_depth_ = 0;
};

}  // namespace lc::client
