#include "editor_client/render/passes/frame_passes.h"

namespace lc::client {

Result<FramePasses> FramePasses::create(VkDevice device, const GpuScene& gpu_scene,
                                        const Scene& scene) {
    Result<std::unique_ptr<GBufferPass>> gbuffer = GBufferPass::create(device, gpu_scene, scene);
    if (!gbuffer) return make_error(gbuffer.error());
    FramePasses passes;
    passes.gbuffer_ = std::move(gbuffer).value();
    return passes;
}

std::array<FramePass*, 3> FramePasses::for_settings(const RenderSettings& settings) {
    FramePass* lighting = &reference_;
    if (mode_needs_tree(settings.mode)) {
        if (settings.criterion == CutCriterion::kRadius)
            lighting = &radius_walk_;
        else if (settings.bound_search == BoundSearch::kWalk)
            lighting = &bound_walk_;
        else
            lighting = &bound_heap_;
    }
    FramePass* output = &tone_map_;
    if (!mode_is_shaded(settings.mode)) output = &cut_view_;
    return {gbuffer_.get(), lighting, output};
}

}  // namespace lc::client
