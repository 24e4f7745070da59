#include "editor_client/render/gpu/gpu_lights.h"

#include <span>

#include "editor_client/render/gpu/storage_upload.h"
#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/status_macros.h"
#include "protocol/channel_records.h"

namespace lc::client {

Status GpuLights::upload(const vk::Context& context, const Scene& scene, const WalkTree* tree) {
    std::vector<GpuLight> scene_leaves;
    std::vector<GpuLight> classic;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const SceneLight& light = scene.lights[i];
        LC_RETURN_IF_ERROR(validate_scene_light(light, i));
        if (light.classic) {
            classic.push_back(make_gpu_light(light));
        } else if (tree == nullptr) {
            scene_leaves.push_back(make_gpu_light(light));
        }
    }
    // The walk tree is uploaded as it is, not copied.
    const std::span<const GpuLight> leaves =
        tree != nullptr ? std::span(tree->leaves) : std::span(scene_leaves);
    const std::span<const GpuTreeNode> nodes =
        tree != nullptr ? std::span(tree->nodes) : std::span<const GpuTreeNode>();
    tree_depth_ = tree != nullptr ? tree->depth : 0;
    if (leaves.size() > UINT32_MAX || nodes.size() > size_t(INT32_MAX) || classic.size() > UINT32_MAX)
        return make_error("too many lights for 32-bit counts");

    LC_RETURN_IF_ERROR(upload_storage(context, leaves_, std::as_bytes(leaves)));
    LC_RETURN_IF_ERROR(upload_storage(context, classic_, std::as_bytes(std::span(classic))));
    LC_RETURN_IF_ERROR(upload_storage(context, nodes_, std::as_bytes(nodes)));
    leaf_count_ = uint32_t(leaves.size());
    classic_count_ = uint32_t(classic.size());
    node_count_ = uint32_t(nodes.size());
    has_tree_ = tree != nullptr;
    return Ok{};
}

}  // namespace lc::client
