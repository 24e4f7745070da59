#include "editor_client/render/passes/frame_passes.h"

#include <spdlog/spdlog.h>

#include "lightcuts/status_macros.h"

namespace lc::client {

Result<FramePasses> FramePasses::create(const vk::Context& context, VkDescriptorSetLayout frame_layout,
                                        const GpuScene& gpu_scene, const Scene& scene,
                                        PrimaryChoice primary) {
    const vk::Device& device = context.device();
    Result<std::unique_ptr<GBufferPass>> gbuffer =
        GBufferPass::create(device.handle(), gpu_scene, scene);
    if (!gbuffer) return make_error(gbuffer.error());
    Result<std::unique_ptr<RealtimePass>> realtime = RealtimePass::create(device, frame_layout);
    if (!realtime) return make_error(realtime.error());
    Result<std::unique_ptr<RestirPass>> restir = RestirPass::create(device, frame_layout);
    if (!restir) return make_error(restir.error());
    Result<std::unique_ptr<ReconstructionPass>> reconstruction = ReconstructionPass::create(device, frame_layout);
    if (!reconstruction) return make_error(reconstruction.error());
    Result<std::unique_ptr<PrimaryRaysPass>> primary_rays =
        PrimaryRaysPass::create(context, frame_layout, gpu_scene, scene);
    if (!primary_rays) return make_error(primary_rays.error());
    FramePasses passes;
    passes.primary_rays_ = std::move(primary_rays).value();
    // Auto: rays on a GPU for a scene without raster-only materials.
    const bool rays_fit = !context.physical().is_software() && passes.primary_rays_->unsupported().empty();
    passes.primary_ = primary == PrimaryChoice::kRays || (primary == PrimaryChoice::kAuto && rays_fit)
                          ? PrimaryVisibility::kRays
                          : PrimaryVisibility::kRaster;
    passes.may_fall_back_ = primary == PrimaryChoice::kAuto;
    passes.gbuffer_ = std::move(gbuffer).value();
    passes.realtime_ = std::move(realtime).value();
    passes.restir_ = std::move(restir).value();
    passes.reconstruction_ = std::move(reconstruction).value();
    return passes;
}

std::array<FramePass*, 3> FramePasses::for_settings(const RenderSettings& settings) {
    FramePass* lighting = &reference_;
    if (settings.mode == RenderMode::kRealtime) {
        lighting = realtime_.get();
    } else if (settings.mode == RenderMode::kRestir) {
        lighting = restir_.get();
    } else if (mode_needs_tree(settings.mode)) {
        if (settings.criterion == CutCriterion::kRadius)
            lighting = &radius_walk_;
        else if (settings.reconstruction_block > 0 && mode_searches_cuts(settings.mode))
            lighting = reconstruction_.get();
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
    if (Status drawn = passes[0]->prepare(pipelines, frame); !drawn) {
        if (passes[0] != primary_rays_.get() || !may_fall_back_) return make_error(drawn.error());
        spdlog::warn("{}: the G-buffer is rasterised instead", drawn.error());
        primary_ = PrimaryVisibility::kRaster;
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


}  // namespace lc::client
