#pragma once
// The Vulkan renderer: one frame's preparation and recording around three
// passes (render/passes/): the G-buffer, lighting (reference, a lightcuts
// algorithm or the real-time mode), then tone mapping or a cut view. What the
// frame reads it owns in parts: the scene's geometry (GpuScene), its lights
// (GpuLights), the occluders (GpuOccluders), the background, the targets,
// the exact clamp's visibility, the measurements (timestamps, counters) and
// the compute passes' set 0 over them (FrameDescriptors). Headless (render()
// + read_*) or recorded into a window's frame (record()).
#include <vulkan/vulkan.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "editor_client/render/gpu/background_buffers.h"
#include "editor_client/render/gpu/frame_descriptors.h"
#include "editor_client/render/gpu/frame_measurements.h"
#include "editor_client/render/gpu/gpu_lights.h"
#include "editor_client/render/gpu/gpu_occluders.h"
#include "editor_client/render/gpu/gpu_scene.h"
#include "editor_client/render/gpu/loop_budget.h"
#include "editor_client/render/passes/frame_passes.h"
#include "editor_client/render/gpu/pipeline_cache.h"
#include "editor_client/render/gpu/pixel_region.h"
#include "editor_client/render/settings/render_settings.h"
#include "editor_client/render/output/render_stats.h"
#include "editor_client/render/gpu/render_targets.h"
#include "editor_client/render/analysis/scene_effects.h"
#include "editor_client/render/gpu/vpl_visibility.h"
#include "editor_client/vk/context.h"
#include "lightcuts/environment.h"
#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/occlusion/shadow_ray.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc::client {

struct RendererOptions {
    uint32_t workgroup_size = 8;  // compute workgroups are size x size
    ShadowMode shadows = ShadowMode::kAuto;  // auto: the scene analysis decides
    // The tree's indirect lights: on (clamped) or off (left out; render --indirect off).
    bool indirect = true;
    // A headless reference frame is submitted in runs of its dispatches, each
    // at most this many light evaluations (with their shadow rays): on
    // lavapipe under load about 2.5 minutes, well within a fence wait (600 s).
    uint64_t reference_evaluations_per_submission = uint64_t(1) << 27;
    // The real-time mode's history: how long, and the spatial filter's fade.
    TemporalPolicy realtime;
    // How the G-buffer is made (render --primary).
    PrimaryChoice primary = PrimaryChoice::kAuto;
    // Reference mode's exact clamp keeps each VPL's visibility for its Newton
    // passes (one bit per pixel and leaf) when it fits this many bytes; a
    // larger frame traces the rays again in every pass.
    uint64_t vpl_visibility_budget_bytes = uint64_t(512) << 20;
};

// The G-buffer as read back, 4 floats per pixel, rows top to bottom.
struct GBufferReadback {
    glm::vec3 eye{0.0f};  // the camera of the frame (the glossy lobe's view)
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> position;  // w = 1 on geometry
    std::vector<float> normal;    // w: roughness
    std::vector<float> albedo;    // base colour, w: metallic
    std::vector<float> emissive;
};

class Renderer {
public:
    // The scene is uploaded once and must outlive the renderer (set_tree reads
    // its lights again); `tree` (may be null) is copied to the GPU as it is
    // (make_walk_tree makes it from the imported tree).
    static Result<std::unique_ptr<Renderer>> create(const vk::Context& context, const Scene& scene,
                                                    const WalkTree* tree,
                                                    const RendererOptions& options = {});
    // A temporary scene would die before the renderer that keeps it (ASan
    // found tests passing one): refused at compile time.
    static Result<std::unique_ptr<Renderer>> create(const vk::Context& context, const Scene&& scene,
                                                    const WalkTree* tree,
                                                    const RendererOptions& options = {}) = delete;
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Replaces the tree (null: none) and re-analyses the effects. Waits for the GPU.
    Status set_tree(const WalkTree* tree);
    bool has_tree() const { return lights_.has_tree(); }
    // The environment pixels without geometry show (null: black, the
    // default); the tree's lights stand for its light. Waits for the GPU.
    Status set_environment(std::shared_ptr<const Environment> environment);
    const Environment* environment() const { return background_.environment(); }
    // What a frame with these settings shows where no geometry is hit
    // (background.h): the environment's parameters and the frame's eye rays.
    GpuBackground background(const RenderSettings& settings) const;
    const SceneEffects& effects() const { return effects_; }

    // Checks settings (render_settings.h's validate, with whether a tree is
    // held) and the device's loop budget.
    Status validate(const RenderSettings& settings) const;
    Status check_loop_budget(const RenderSettings& settings) const;

    // Records every pass of one frame into `cmd`. All storage images end in
    // VK_IMAGE_LAYOUT_GENERAL; display_image() holds the 8-bit result.
    Status record(VkCommandBuffer cmd, const RenderSettings& settings);
    // Records part of a frame: the lighting and output passes over `regions`
    // only (origins on workgroup boundaries, inside the image). A new image
    // (`continues_image` false) draws the G-buffer first; a continued one
    // keeps the G-buffer and what earlier regions lit, and fails when the
    // targets were remade since (another size was rendered in between).
    Status record_regions(VkCommandBuffer cmd, const RenderSettings& settings,
                          std::span<const PixelRegion> regions, bool continues_image);
    // Records the output pass alone over `regions` of the image the last
    // frame lit (same size): what is lit already, at a new exposure.
    Status record_output(VkCommandBuffer cmd, const RenderSettings& settings,
                         std::span<const PixelRegion> regions);
    uint32_t workgroup_size() const { return options_.workgroup_size; }

    // Headless: records, submits, waits, and gathers statistics (a long
    // reference over several submissions, its timings and counters summed).
    Result<RenderStats> render(const RenderSettings& settings);
    // The same over `regions` of the image only (record_regions' rules; a new
    // image), its statistics over their pixels: a reference strided over tiles.
    Result<RenderStats> render(const RenderSettings& settings, std::span<const PixelRegion> regions);
    // Headless: rasterises the G-buffer alone (no lighting, no output) for
    // read_gbuffer(), e.g. the eye rays of a supersampled frame.
    Status render_gbuffer(const RenderSettings& settings);
    // Renders a 16x16 frame with these settings' pipelines, so that the next
    // full frame's timing is the work alone: lavapipe compiles a pipeline's
    // shaders on its first dispatch (~0.4 s for the lightcuts shader), inside
    // the GPU timestamps. The last frame's read-backs are lost.
    Status warm_up(const RenderSettings& settings);

    // Results of the last completed frame.
    Result<PassTimings> read_timings() const;
    Result<GpuFrameCounters> read_counters() const;
    Result<std::vector<float>> read_hdr() const;        // RGBA float per pixel
    Result<std::vector<uint8_t>> read_display() const;  // RGBA8 per pixel
    Result<std::vector<uint32_t>> read_cuts() const;    // (size, hash) per pixel
    // The indirect light before the clamp and what it removed, over the
    // frame's pixels (walk_states; effects_.indirect_clamp only).
    Status read_clamped_energy(RenderStats& stats) const;
    Result<GBufferReadback> read_gbuffer() const;

    const vk::Image& display_image() const { return targets_.display; }
    uint32_t width() const { return targets_.width; }
    uint32_t height() const { return targets_.height; }
    // Counts for stats: leaves evaluated by reference mode, classic lights, tree nodes.
    uint32_t leaf_count() const { return lights_.leaf_count(); }
    uint32_t classic_count() const { return lights_.classic_count(); }
    uint32_t node_count() const { return lights_.node_count(); }
    uint32_t tree_depth() const { return lights_.tree_depth(); }
    // The occluders shadow rays test (SceneEffects::occluders, rebuilt with the tree).
    const ShadowBvh& shadow_bvh() const { return occluders_.bvh(); }
    float shadow_bias() const { return occluders_.bias(); }
    // The real-time mode: frames in its history after the last frame (its mean is the image).
    uint32_t realtime_frames() const { return passes_->realtime().frames_accumulated(); }
    // The ReSTIR mode's likewise.
    uint32_t restir_frames() const { return passes_->restir().frames_accumulated(); }
    // The next real-time or ReSTIR frame starts a history of its own, whatever the last one was.
    void restart_realtime() {
        passes_->realtime().drop_history();
        passes_->restir().drop_history();
    }
    // Reference mode's dispatches: leaves per dispatch so that none exceeds
    // the device's loop budget (all of them in one on devices without one).
    uint32_t reference_chunk() const;
    // The exact clamp's passes after the reference's sums (0 outside reference mode or without VPLs).
    uint32_t reference_clamp_passes(const RenderSettings& settings) const;

private:
    Renderer(const vk::Context& context, const Scene& scene, const RendererOptions& options);

    Status create_frame_resources();
    Status prepare_vpl_visibility(const RenderSettings& settings);
    // Shadow rays are traced: the analysis asked for them and something occludes.
    bool traces_shadows() const { return effects_.shadows && !occluders_.bvh().empty(); }
    LoopWork loop_work() const;
    // Remade (contents lost) when the size differs: the result says whether.
    Result<bool> ensure_targets(uint32_t width, uint32_t height);
    Status check_regions(std::span<const PixelRegion> regions, uint32_t width, uint32_t height) const;
    void update_frame_descriptors();
    Frame make_frame(const RenderSettings& settings) const;
    // The one place a frame is prepared: settings and regions checked, targets
    // of its size, the exact clamp's visibility (a new image only), the set
    // written and the passes' pipelines found. Returns the frame and its passes in order.
    struct PreparedFrame {
        Frame frame;
        std::array<FramePass*, 3> passes{};
    };
    Result<PreparedFrame> prepare_frame(const RenderSettings& settings, std::span<const PixelRegion> regions,
                                        bool continues_image);
    // Records a prepared frame's passes between its measurements.
    void record_prepared(VkCommandBuffer cmd, const PreparedFrame& prepared);
    Result<std::vector<std::byte>> read_image(const vk::Image& image) const;
    // A headless frame's submissions, their GPU times and counters summed.
    struct SubmittedFrame {
        PassTimings timings;
        GpuFrameCounters counters;
        double wall_ms = 0.0;
        uint32_t submissions = 0;
    };
    Result<SubmittedFrame> submit_frame(PreparedFrame prepared);
    RenderStats frame_stats(const RenderSettings& settings, const SubmittedFrame& frame) const;
    void add_settings_stats(const RenderSettings& settings, RenderStats& stats) const;
    Status add_cut_stats(const RenderSettings& settings, std::span<const PixelRegion> regions,
                         RenderStats& stats) const;

    const vk::Context& context_;
    const Scene& scene_;
    RendererOptions options_;
    SceneEffects effects_;
    GpuScene gpu_scene_;
    GpuLights lights_;
    GpuOccluders occluders_;
    BackgroundBuffers background_;
    RenderTargets targets_;
    VplVisibility vpl_visibility_;
    FrameMeasurements measurements_;
    FrameDescriptors descriptors_;
    PipelineCache pipelines_;
    std::optional<FramePasses> passes_;  // created once the scene is on the GPU
};

}  // namespace lc::client
