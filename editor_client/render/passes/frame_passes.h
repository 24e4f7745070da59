#pragma once
// Every pass a frame can use, and the three (G-buffer, lighting, output) that
// render a given mode and cut criterion.
#include <array>
#include <memory>

#include "editor_client/render/passes/bound_heap_pass.h"
#include "editor_client/render/passes/bound_walk_pass.h"
#include "editor_client/render/passes/cut_view_pass.h"
#include "editor_client/render/passes/gbuffer_pass.h"
#include "editor_client/render/passes/primary_rays_pass.h"
#include "editor_client/render/passes/radius_walk_pass.h"
#include "editor_client/render/passes/realtime_pass.h"
#include "editor_client/render/passes/reconstruction_pass.h"
#include "editor_client/render/passes/reference_pass.h"
#include "editor_client/render/passes/restir_pass.h"
#include "editor_client/render/passes/tone_map_pass.h"

namespace lc::client {

class FramePasses {
public:
    // Both must outlive the passes.
    // `frame_layout` is the compute passes' set 0.
    static Result<FramePasses> create(const vk::Context& context, VkDescriptorSetLayout frame_layout,
                                      const GpuScene& gpu_scene, const Scene& scene,
                                      PrimaryChoice primary);

    // The passes that render `settings`, in recording order.
    std::array<FramePass*, 3> for_settings(const RenderSettings& settings);
    // Prepares the passes that render frame.settings and returns them. Where
    // auto chose rays and the driver cannot build their pipeline, the frame
    // (and every later one) falls back to the raster pass, with a warning.
    Result<std::array<FramePass*, 3>> prepare(PipelineCache& pipelines, const Frame& frame);
    // The G-buffer pass alone (Renderer::render_gbuffer): raster or rays.
    FramePass& gbuffer();
    // How the G-buffer is made (PrimaryChoice's rule, the same for every mode).
    PrimaryVisibility primary() const { return primary_; }
    RealtimePass& realtime() { return *realtime_; }
    const RealtimePass& realtime() const { return *realtime_; }
    RestirPass& restir() { return *restir_; }
    const RestirPass& restir() const { return *restir_; }
    const BoundHeapPass& bound_heap() const { return bound_heap_; }

private:
    std::unique_ptr<GBufferPass> gbuffer_;
    std::unique_ptr<PrimaryRaysPass> primary_rays_;
    PrimaryVisibility primary_ = PrimaryVisibility::kRaster;
    bool may_fall_back_ = false;  // auto chose: a driver refusing the rays gets raster
    ReferencePass reference_;
    RadiusWalkPass radius_walk_;
    BoundWalkPass bound_walk_;
    BoundHeapPass bound_heap_;
    std::unique_ptr<RealtimePass> realtime_;
    std::unique_ptr<RestirPass> restir_;
    std::unique_ptr<ReconstructionPass> reconstruction_;
    ToneMapPass tone_map_;
    CutViewPass cut_view_;
};

}  // namespace lc::client
