#include "editor_client/render/passes/frame_passes.h"

namespace lc::client {

Result<FramePasses> FramePasses::create(const vk::Device& device, VkDescriptorSetLayout frame_layout,
                                        const GpuScene& gpu_scene, const Scene& scene) {
    Result<std::unique_ptr<GBufferPass>> gbuffer =
        GBufferPass::create(device.handle(), gpu_scene, scene);
    if (!gbuffer) return make_error(gbuffer.error());
    Result<std::unique_ptr<RealTimePass>> real_time = RealTimePass::create(device, frame_layout);
    if (!real_time) return make_error(real_time.error());
    FramePasses passes;
    passes.gbuffer_ = std::move(gbuffer).value();
    passes.real_time_ = std::move(real_time).value();
    return passes;
}

std::array<FramePass*, 3> FramePasses::for_settings(const RenderSettings& settings) {
    FramePass* lighting = &reference_;
    if (settings.mode == RenderMode::kRealTime) {
        lighting = real_time_.get();
    } else if (mode_needs_tree(settings.mode)) {
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
