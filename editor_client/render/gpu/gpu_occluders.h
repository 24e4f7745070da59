#pragma once
// What shadow rays test, on the GPU: the BVH over the triangles that can hide
// a light (SceneEffects::occluders), its triangles in leaf order, the
// alpha-masked ones with their masks and texels, and the rays' offset.
#include <vulkan/vulkan.h>

#include "editor_client/render/analysis/scene_effects.h"
#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"
#include "lightcuts/occlusion/shadow_bvh.h"

namespace lc::client {

class GpuOccluders {
public:
    // Builds the BVH over the effects' occluders and uploads it.
    Status upload(const vk::Context& context, const SceneEffects& effects);
    bool uploaded() const { return bool(nodes_); }
    // The scene's bounds hold its lights: set again with every tree.
    void set_bias(const Scene& scene) { bias_ = shadow_ray_bias(scene); }

    const ShadowBvh& bvh() const { return bvh_; }
    float bias() const { return bias_; }
    VkBuffer nodes() const { return nodes_.handle(); }
    VkBuffer triangles() const { return triangles_.handle(); }
    VkBuffer masked_triangles() const { return masked_triangles_.handle(); }
    VkBuffer alpha_masks() const { return alpha_masks_.handle(); }
    VkBuffer mask_texels() const { return mask_texels_.handle(); }

private:
    ShadowBvh bvh_;
    float bias_ = 0.0f;
    vk::Buffer nodes_;             // GpuWideBvhNode, root first
    vk::Buffer triangles_;         // GpuShadowTriangle, in leaf order
    vk::Buffer masked_triangles_;  // GpuMaskedTriangle (alpha-masked occluders)
    vk::Buffer alpha_masks_;       // GpuAlphaMask
    vk::Buffer mask_texels_;       // GpuMaskTexels
};

}  // namespace lc::client
