#include "editor_client/render/gpu_lights.h"

#include <span>

#include "editor_client/render/storage_upload.h"
#include "lightcuts/gpu_layout.h"
#include "lightcuts/status_macros.h"
#include "protocol/channel_records.h"

namespace lc::client {

Result<std::vector<GpuTreeNode>> GpuLights::upload(const vk::Context& context, const Scene& scene,
                                                   const LightTree* tree) {
    std::vector<GpuLight> leaves;
    std::vector<GpuLight> classic;
    std::vector<GpuTreeNode> nodes;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const SceneLight& light = scene.lights[i];
        LC_RETURN_IF_ERROR(validate_scene_light(light, i));
        if (light.classic) {
            classic.push_back(make_gpu_light(light));
        } else if (tree == nullptr) {
            leaves.push_back(make_gpu_light(light));
        }
    }
    tree_depth_ = 0;
    if (tree != nullptr) {
        Result<GpuTree> gpu_tree = make_gpu_tree(*tree);
        if (!gpu_tree) return make_error("light tree: " + gpu_tree.error());
        leaves = std::move(gpu_tree->leaves);
        nodes = std::move(gpu_tree->nodes);
        tree_depth_ = gpu_tree->depth;
    }
    if (leaves.size() > UINT32_MAX || nodes.size() > size_t(INT32_MAX) || classic.size() > UINT32_MAX)
        return make_error("too many lights for 32-bit counts");

    LC_RETURN_IF_ERROR(upload_storage(context, leaves_, std::as_bytes(std::span(leaves))));
    LC_RETURN_IF_ERROR(upload_storage(context, classic_, std::as_bytes(std::span(classic))));
    LC_RETURN_IF_ERROR(upload_storage(context, nodes_, std::as_bytes(std::span(nodes))));
    leaf_count_ = uint32_t(leaves.size());
    classic_count_ = uint32_t(classic.size());
    node_count_ = uint32_t(nodes.size());
    has_tree_ = tree != nullptr;
    return nodes;
}

}  // namespace lc::client
