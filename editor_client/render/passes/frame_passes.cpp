#include "editor_client/render/passes/frame_passes.h"

#include <spdlog/spdlog.h>

#include "editor_client/render/primary_geometry.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

Result<FramePasses> FramePasses::create(const vk::Context& context, VkDescriptorSetLayout frame_layout,
                                        const GpuScene& gpu_scene, const Scene& scene,
                                        PrimaryChoice primary) {
    const vk::Device& device = context.device();
    Result<std::unique_ptr<GBufferPass>> gbuffer =
        GBufferPass::create(device.handle(), gpu_scene, scene);
    if (!gbuffer) return make_error(gbuffer.error());
    Result<std::unique_ptr<RealTimePass>> real_time = RealTimePass::create(device, frame_layout);
    if (!real_time) return make_error(real_time.error());
    Result<std::unique_ptr<PrimaryRaysPass>> primary_rays =
        PrimaryRaysPass::create(context, frame_layout, gpu_scene, scene);
    if (!primary_rays) return make_error(primary_rays.error());
    FramePasses passes;
    passes.primary_rays_ = std::move(primary_rays).value();
    passes.primary_choice_ = primary;
    passes.rays_fit_ = !context.physical().is_software() && primary_rays_unsupported(gpu_scene).empty();
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
    return {&gbuffer(), lighting, output};
}

Result<std::array<FramePass*, 3>> FramePasses::prepare(PipelineCache& pipelines, const Frame& frame) {
    std::array<FramePass*, 3> passes = for_settings(*frame.settings);
    if (Status rays = passes[0]->prepare(pipelines, frame); !rays) {
        if (passes[0] != primary_rays_.get() || primary_choice_ != PrimaryChoice::kAuto)
            return make_error(rays.error());
        spdlog::warn("{}: the G-buffer is rasterised instead", rays.error());
        rays_fit_ = false;
        passes[0] = gbuffer_.get();
        LC_RETURN_IF_ERROR(passes[0]->prepare(pipelines, frame));
    }
    for (size_t i = 1; i < passes.size(); ++i) LC_RETURN_IF_ERROR(passes[i]->prepare(pipelines, frame));
    return passes;
}

FramePass& FramePasses::gbuffer() {
    if (primary() == PrimaryVisibility::kRays) return *primary_rays_;
    return *gbuffer_;
}

PrimaryVisibility FramePasses::primary() const {
    if (primary_choice_ == PrimaryChoice::kRays) return PrimaryVisibility::kRays;
    if (primary_choice_ == PrimaryChoice::kRaster) return PrimaryVisibility::kRaster;
    return rays_fit_ ? PrimaryVisibility::kRays : PrimaryVisibility::kRaster;
}

}  // namespace lc::client
