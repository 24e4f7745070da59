#include "editor_client/render/gpu/gpu_occluders.h"

#include <spdlog/spdlog.h>

#include <span>
#include <string>

#include "editor_client/render/gpu/storage_upload.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

Status GpuOccluders::upload(const vk::Context& context, const SceneEffects& effects) {
    bvh_ = ShadowBvh::build(effects.occluders, effects.occluder_masks);
    const ShadowBvhStats& s = bvh_.stats();
    spdlog::debug(
        "shadow BVH: {} triangles ({} degenerate, {} not casting, {} masked) in {} nodes, depth {}; "
        "4-wide: {} nodes, {} leaves, depth {}, stack {} (SAH to depth {})",
        s.triangles, s.skipped_degenerate, s.skipped_non_casting, s.masked, s.nodes, s.depth, s.wide_nodes,
        s.wide_leaves, s.wide_depth, s.stack_need, s.max_sah_depth);
    // The build keeps the walk within the shaders' stack; a BVH that is not is refused.
    if (s.stack_need > kBvhStackSize)
        return make_error("shadow BVH: its walk needs " + std::to_string(s.stack_need) +
                          " stack entries, more than the shaders' " + std::to_string(kBvhStackSize));
    LC_RETURN_IF_ERROR(upload_storage(context, nodes_, std::as_bytes(std::span(bvh_.gpu_wide_nodes()))));
    LC_RETURN_IF_ERROR(
        upload_storage(context, masked_triangles_, std::as_bytes(std::span(bvh_.gpu_masked_triangles()))));
    LC_RETURN_IF_ERROR(upload_storage(context, alpha_masks_, std::as_bytes(std::span(bvh_.gpu_alpha_masks()))));
    LC_RETURN_IF_ERROR(upload_storage(context, mask_texels_, std::as_bytes(std::span(bvh_.gpu_mask_texels()))));
    return upload_storage(context, triangles_, std::as_bytes(std::span(bvh_.gpu_triangles())));
}

}  // namespace lc::client
