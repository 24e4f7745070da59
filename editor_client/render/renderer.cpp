#include "editor_client/render/renderer.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "lightcuts/device/indirect_clamp.glsl.h"
#include "editor_client/render/background.h"
#include "editor_client/render/passes/reconstruction_records.h"
#include "editor_client/render/passes/reference_pass.h"
#include "editor_client/vk/barriers.h"
#include "editor_client/vk/vk_result.h"

namespace lc::client {
namespace {

template <typename T>
std::vector<T> reinterpret_texels(const std::vector<std::byte>& bytes) {
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    return out;
}

}  // namespace

Renderer::Renderer(const vk::Context& context, const Scene& scene, const RendererOptions& options)
    : context_(context),
      scene_(scene),
      options_(options),
      pipelines_(context.device().handle()) {}

Renderer::~Renderer() {
    // Nothing may be destroyed while the GPU still uses it.
    if (context_.device().handle() != VK_NULL_HANDLE) vkDeviceWaitIdle(context_.device().handle());
}

Result<std::unique_ptr<Renderer>> Renderer::create(const vk::Context& context, const Scene& scene,
                                                   const WalkTree* tree, const RendererOptions& options) {
    const uint32_t max_invocations =
        context.physical().properties.limits.maxComputeWorkGroupInvocations;
    if (options.workgroup_size == 0 ||
        options.workgroup_size * options.workgroup_size > max_invocations)
        return make_error("workgroup size " + std::to_string(options.workgroup_size) + "x" +
                          std::to_string(options.workgroup_size) + " exceeds the device's " +
                          std::to_string(max_invocations) + " invocations per workgroup");
    std::unique_ptr<Renderer> renderer(new Renderer(context, scene, options));
    Result<GpuScene> gpu_scene = GpuScene::upload(context, scene);
    if (!gpu_scene) return make_error(gpu_scene.error());
    renderer->gpu_scene_ = std::move(gpu_scene).value();
    LC_RETURN_IF_ERROR(renderer->create_frame_resources());
    Result<FramePasses> passes = FramePasses::create(
        context, renderer->descriptors_.layout(), renderer->gpu_scene_, scene, options.primary);
    if (!passes) return make_error(passes.error());
    renderer->passes_.emplace(std::move(passes).value());
    renderer->passes_->realtime().set_policy(options.realtime);
    renderer->passes_->restir().set_policy(options.realtime);
    LC_RETURN_IF_ERROR(renderer->set_tree(tree));
    return renderer;
}

Status Renderer::create_frame_resources() {
    LC_RETURN_IF_ERROR(descriptors_.create(context_.device().handle()));
    LC_RETURN_IF_ERROR(measurements_.create(context_));
    if (Result<bool> made = vpl_visibility_.ensure(context_, sizeof(GpuVisibilityBits)); !made)
        return make_error(made.error());
    return background_.create(context_);
}

Status Renderer::set_tree(const WalkTree* tree) {
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    Status uploaded = lights_.upload(context_, scene_, tree);
    descriptors_.mark_dirty();
    if (!uploaded) return uploaded;
    const std::span<const GpuTreeNode> nodes =
        tree != nullptr ? std::span(tree->nodes) : std::span<const GpuTreeNode>();
    LC_RETURN_IF_ERROR(passes_->realtime().set_tree_nodes(context_.command_pool(), nodes));
    LC_RETURN_IF_ERROR(passes_->restir().set_tree_nodes(context_.command_pool(), nodes));
    SceneEffects effects = analyse_scene_effects(scene_, tree, options_.shadows, options_.indirect);
    // Which surfaces can hide a light depends on where the lights are; most
    // light edits leave them as they were, and the BVH stays.
    const bool same_occluders = occluders_.uploaded() && effects.occluders == effects_.occluders &&
                                effects.occluder_masks == effects_.occluder_masks;
    effects_ = std::move(effects);
    if (!same_occluders) {
        descriptors_.mark_dirty();
        LC_RETURN_IF_ERROR(occluders_.upload(context_, effects_));
    }
    occluders_.set_bias(scene_);
    for (const EffectDecision& d : effects_.decisions)
        spdlog::debug("effect {}: {} ({})", d.name, d.simulated ? "simulated" : "skipped",
                      d.reason);
    // The pipelines are keyed by the effects' specialization constants: a
    // frame after a change finds (or builds) the ones that match.
    restart_realtime();
    return Ok{};
}

Status Renderer::set_environment(std::shared_ptr<const Environment> environment) {
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    descriptors_.mark_dirty();
    LC_RETURN_IF_ERROR(background_.set_environment(context_, std::move(environment)));
    restart_realtime();
    return Ok{};
}

GpuBackground Renderer::background(const RenderSettings& settings) const {
    return make_gpu_background(background_.environment(), settings, settings.width, settings.height,
                               scene_.bounds_min, scene_.bounds_max);
}

Status Renderer::validate(const RenderSettings& settings) const {
    ValidationContext context;
    context.has_tree = lights_.has_tree();
    LC_RETURN_IF_ERROR(client::validate(settings, context));
    // The shared walk lays a subgroup over a 4x2 block of an 8x8 workgroup.
    if (settings.share_cuts && mode_needs_tree(settings.mode) && options_.workgroup_size != 8)
        return make_error("shared cuts need 8x8 workgroups, not " +
                          std::to_string(options_.workgroup_size) + "x" +
                          std::to_string(options_.workgroup_size));
    return check_loop_budget(settings);
}

LoopWork Renderer::loop_work() const {
    LoopWork work;
    work.leaf_count = lights_.leaf_count();
    work.classic_count = lights_.classic_count();
    work.node_count = lights_.node_count();
    work.shadow_bvh = effects_.shadows ? &occluders_.bvh() : nullptr;
    return work;
}

uint32_t Renderer::reference_clamp_passes(const RenderSettings& settings) const {
    // The reference clamps its VPLs exactly, over passes of its own (reference.comp).
    const bool vpls = effects_.indirect_lights > effects_.indirect_patches;
    if (settings.mode != RenderMode::kReference || !effects_.indirect_clamp || !vpls) return 0;
    return device::kExactClampPasses;
}

uint32_t Renderer::reference_chunk() const {
    return client::reference_chunk(context_.physical().quirks, loop_work());
}

Status Renderer::check_loop_budget(const RenderSettings& settings) const {
    return client::check_loop_budget(context_.physical().quirks, loop_work(), settings);
}

Result<bool> Renderer::ensure_targets(uint32_t width, uint32_t height) {
    if (targets_.width == width && targets_.height == height) return false;
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    Result<RenderTargets> targets = RenderTargets::create(context_.device(), width, height);
    if (!targets) return make_error(targets.error());
    targets_ = std::move(targets).value();
    descriptors_.mark_dirty();
    return true;
}

Status Renderer::check_regions(std::span<const PixelRegion> regions, uint32_t width,
                               uint32_t height) const {
    const uint32_t size = options_.workgroup_size;
    for (const PixelRegion& r : regions) {
        if (r.width == 0 || r.height == 0 || r.x % size != 0 || r.y % size != 0 ||
            r.x >= width || r.y >= height || r.width > width - r.x || r.height > height - r.y)
            return make_error("pixel region " + std::to_string(r.x) + "," + std::to_string(r.y) +
                              " " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                              " is not inside the " + std::to_string(width) + "x" +
                              std::to_string(height) + " image on " + std::to_string(size) +
                              "-pixel workgroup boundaries");
    }
    return Ok{};
}

void Renderer::update_frame_descriptors() {
    descriptors_.update(context_.device().handle(), targets_, lights_, occluders_, background_,
                        FrameBuffers{measurements_.counters(), vpl_visibility_.buffer()});
}

Frame Renderer::make_frame(const RenderSettings& settings) const {
    Frame frame;
    frame.settings = &settings;
    frame.targets = &targets_;
    frame.effects = &effects_;
    frame.shadows = traces_shadows();
    frame.alpha_masks = frame.shadows && occluders_.bvh().stats().masked > 0;
    frame.workgroup_size = options_.workgroup_size;
    frame.compute_layout = descriptors_.compute_layout();
    frame.frame_set = descriptors_.set();
    frame.reference_chunk = reference_chunk();
    GpuFrameConstants& constants = frame.constants;
    constants.width = targets_.width;
    constants.height = targets_.height;
    constants.leaf_count = lights_.leaf_count();
    constants.classic_count = lights_.classic_count();
    constants.node_count = lights_.node_count();
    constants.exposure = settings.exposure;
    constants.scale_bar_rows =
        settings.mode == RenderMode::kCutSize ? std::min(kScaleBarRows, targets_.height / 4) : 0u;
    constants.shadow_bias = frame.shadows ? occluders_.bias() : 0.0f;
    constants.bvh_node_count = frame.shadows ? occluders_.bvh().walk_steps() : 0u;
    constants.light_begin = 0;
    constants.light_end = lights_.leaf_count();
    constants.eye = settings.camera.eye;
    constants.clamp_passes = reference_clamp_passes(settings);
    constants.vpl_visibility_stride = constants.clamp_passes > 0 ? vpl_visibility_.stride() : 0u;
    return frame;
}

// The exact clamp's kept visibility for a frame with these settings: one bit
// per pixel and leaf, within the budget (else Newton's passes trace again).
Status Renderer::prepare_vpl_visibility(const RenderSettings& settings) {
    const bool clamps = reference_clamp_passes(settings) > 0 && traces_shadows();
    Result<bool> remade =
        vpl_visibility_.prepare(context_, clamps, lights_.leaf_count(), uint64_t(settings.width) * settings.height,
                                options_.vpl_visibility_budget_bytes);
    if (!remade) return make_error(remade.error());
    if (*remade) descriptors_.mark_dirty();
    return Ok{};
}

Result<Renderer::PreparedFrame> Renderer::prepare_frame(const RenderSettings& settings,
                                                        std::span<const PixelRegion> regions,
                                                        bool continues_image) {
    LC_RETURN_IF_ERROR(validate(settings));
    LC_RETURN_IF_ERROR(check_regions(regions, settings.width, settings.height));
    Result<bool> remade = ensure_targets(settings.width, settings.height);
    if (!remade) return make_error(remade.error());
    if (*remade && continues_image)
        return make_error("the image to continue was lost: another size was rendered since");
    if (!continues_image) LC_RETURN_IF_ERROR(prepare_vpl_visibility(settings));
    update_frame_descriptors();
    PreparedFrame prepared{make_frame(settings)};
    prepared.frame.regions = regions;
    prepared.frame.continues_image = continues_image;
    Result<std::array<FramePass*, 3>> passes = passes_->prepare(pipelines_, prepared.frame);
    if (!passes) return make_error(passes.error());
    prepared.passes = *passes;
    return prepared;
}

Status Renderer::record(VkCommandBuffer cmd, const RenderSettings& settings) {
    const PixelRegion whole{0, 0, settings.width, settings.height};
    return record_regions(cmd, settings, std::span(&whole, 1), false);
}

Status Renderer::record_regions(VkCommandBuffer cmd, const RenderSettings& settings,
                                std::span<const PixelRegion> regions, bool continues_image) {
    Result<PreparedFrame> prepared = prepare_frame(settings, regions, continues_image);
    if (!prepared) return make_error(prepared.error());
    record_prepared(cmd, *prepared);
    return Ok{};
}

void Renderer::record_prepared(VkCommandBuffer cmd, const PreparedFrame& prepared) {
    const Frame& frame = prepared.frame;
    const RenderSettings& settings = *frame.settings;
    targets_.gbuffer_eye = settings.camera.eye;
    measurements_.begin(cmd);
    const GpuBackground background = this->background(settings);
    vkCmdUpdateBuffer(cmd, background_.frame(), 0, sizeof(background), &background);
    // The clamp's per-pixel statistics: background pixels keep their zeros. Only
    // when an image starts: a continued one (the next submission of a reference,
    // the next tiles of a progressive view) carries its sums in the walk states.
    if (effects_.indirect_clamp && !frame.continues_image)
        vkCmdFillBuffer(cmd, targets_.walk_states.handle(), 0, VK_WHOLE_SIZE, 0);
    if (frame.constants.vpl_visibility_stride > 0 && !frame.continues_image)
        vkCmdFillBuffer(cmd, vpl_visibility_.buffer(), 0, VK_WHOLE_SIZE, 0);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       kComputeStage, kStorageReadWrite);
    uint32_t pass_number = 0;
    for (const FramePass* pass : prepared.passes) {
        // A continued image keeps its G-buffer: the pass's time slot stays, empty.
        const bool skipped = frame.continues_image && pass == prepared.passes.front();
        if (!skipped) pass->record(cmd, frame);
        measurements_.end_pass(cmd, pass->last_stage(), ++pass_number);
    }
    if (settings.mode == RenderMode::kRealtime) passes_->realtime().advance();
    if (settings.mode == RenderMode::kRestir) passes_->restir().advance();

    // Results become readable by copies (read-backs, blits) and by the host (counters).
    vk::memory_barrier(cmd, kComputeStage, kStorageWrite,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
}

Status Renderer::render_gbuffer(const RenderSettings& settings) {
    LC_RETURN_IF_ERROR(validate(settings));
    LC_RETURN_IF_ERROR(ensure_targets(settings.width, settings.height));
    update_frame_descriptors();
    const Frame frame = make_frame(settings);
    FramePass& gbuffer = passes_->gbuffer();
    LC_RETURN_IF_ERROR(gbuffer.prepare(pipelines_, frame));
    targets_.gbuffer_eye = settings.camera.eye;
    return context_.command_pool().run_one_time(context_.device(), [&](VkCommandBuffer cmd) {
        gbuffer.record(cmd, frame);
        vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | kComputeStage,
                           VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    });
}

Status Renderer::record_output(VkCommandBuffer cmd, const RenderSettings& settings,
                               std::span<const PixelRegion> regions) {
    if (targets_.width != settings.width || targets_.height != settings.height)
        return make_error("no lit image of this size to tone-map again");
    Result<PreparedFrame> prepared = prepare_frame(settings, regions, true);
    if (!prepared) return make_error(prepared.error());
    prepared->passes.back()->record(cmd, prepared->frame);
    vk::memory_barrier(cmd, kComputeStage, kStorageWrite, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT);
    return Ok{};
}

Status Renderer::warm_up(const RenderSettings& settings) {
    RenderSettings tiny = settings;
    tiny.width = tiny.height = 16;
    Result<RenderStats> stats = render(tiny);
    if (!stats) return make_error(stats.error());
    return Ok{};
}

Result<RenderStats> Renderer::render(const RenderSettings& settings) {
    const PixelRegion whole{0, 0, settings.width, settings.height};
    return render(settings, std::span(&whole, 1));
}

Result<RenderStats> Renderer::render(const RenderSettings& settings,
                                     std::span<const PixelRegion> regions) {
    // Targets, the set and the pipelines before the clock starts: wall_ms is the frame.
    Result<PreparedFrame> prepared = prepare_frame(settings, regions, false);
    if (!prepared) return make_error(prepared.error());
    Result<SubmittedFrame> frame = submit_frame(*prepared);
    if (!frame) return make_error(frame.error());
    RenderStats stats = frame_stats(settings, *frame);
    add_settings_stats(settings, stats);
    if (effects_.indirect_clamp) LC_RETURN_IF_ERROR(read_clamped_energy(stats));
    LC_RETURN_IF_ERROR(add_cut_stats(settings, regions, stats));
    stats.effects_simulated = effects_.simulated();
    stats.effects_skipped = effects_.skipped();
    stats.validation_messages = context_.validation_message_count();
    stats.validation_enabled = context_.validation_enabled();
    return stats;
}

// A long reference goes in several submissions, each within a fence wait: the
// first starts the image, the others continue it.
Result<Renderer::SubmittedFrame> Renderer::submit_frame(PreparedFrame prepared) {
    std::vector<DispatchRange> submissions{DispatchRange{}};
    if (prepared.frame.settings->mode == RenderMode::kReference)
        submissions = reference_submissions(prepared.frame, options_.reference_evaluations_per_submission);
    const auto start = std::chrono::steady_clock::now();
    SubmittedFrame submitted;
    for (size_t s = 0; s < submissions.size(); ++s) {
        prepared.frame.continues_image = s > 0;
        prepared.frame.reference_dispatches = submissions[s];
        LC_RETURN_IF_ERROR(context_.command_pool().run_one_time(
            context_.device(), [&](VkCommandBuffer cmd) { record_prepared(cmd, prepared); }));
        Result<PassTimings> part_timings = measurements_.read_timings();
        if (!part_timings) return make_error(part_timings.error());
        add_timings(submitted.timings, *part_timings);
        add_counters(submitted.counters, measurements_.read_counters());
    }
    submitted.wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    submitted.submissions = uint32_t(submissions.size());
    return submitted;
}

// What every frame reports: the scene's lights, the pass times, the GPU's counters.
RenderStats Renderer::frame_stats(const RenderSettings& settings, const SubmittedFrame& frame) const {
    RenderStats stats;
    stats.mode = render_mode_name(settings.mode);
    stats.criterion = mode_searches_cuts(settings.mode) ? criterion_name(settings.criterion)
                      : settings.mode == RenderMode::kRealtime ? "stochastic"
                      : settings.mode == RenderMode::kRestir   ? "restir"
                                                               : "none";
    stats.device = context_.physical().name();
    stats.width = settings.width;
    stats.height = settings.height;
    stats.lights = uint64_t(lights_.leaf_count()) + lights_.classic_count();
    stats.tree_lights = lights_.has_tree() ? lights_.leaf_count() : 0;
    stats.classic_lights = lights_.classic_count();
    stats.nodes = lights_.node_count();
    stats.tree_depth = lights_.tree_depth();
    stats.timing.wall_ms = frame.wall_ms;
    stats.timing.submissions = frame.submissions;

    stats.timing.render_ms = frame.timings.total_ms;
    stats.timing.gbuffer_ms = frame.timings.gbuffer_ms;
    stats.primary = primary_visibility_name(passes_->primary());
    stats.timing.lighting_ms = frame.timings.lighting_ms;
    stats.timing.output_ms = frame.timings.output_ms;

    const GpuFrameCounters& counters = frame.counters;
    stats.cuts.max_cut = counters.max_cut;
    stats.geometry_pixels = counters.geometry_pixels;
    stats.nonfinite_pixels = counters.nonfinite_pixels;
    stats.cuts.max_cut_hits = counters.max_cut_hits;
    stats.cuts.loop_limit_stops = counters.loop_limit_stops;
    stats.reconstruction.fallbacks = counters.reconstruction_fallbacks;
    stats.shadows.simulated = traces_shadows();
    stats.shadows.rays = (uint64_t(counters.shadow_rays_high) << 32) | counters.shadow_rays;
    stats.shadows.triangles = occluders_.bvh().stats().triangles;
    stats.shadows.bvh_nodes = occluders_.bvh().stats().nodes;
    if (effects_.indirect_lights > 0) {
        stats.indirect.mode = effects_.indirect_off ? "off" : "on";
        stats.indirect.lights = effects_.indirect_lights;
        stats.indirect.patches = effects_.indirect_patches;
    }
    return stats;
}

// What the frame's mode and cut search were asked for.
void Renderer::add_settings_stats(const RenderSettings& settings, RenderStats& stats) const {
    stats.indirect.reference_clamp_passes = reference_clamp_passes(settings);
    stats.indirect.reference_visibility_kept =
        stats.indirect.reference_clamp_passes > 0 && vpl_visibility_.stride() > 0;
    if (settings.mode == RenderMode::kReference) {
        const uint32_t chunk = reference_chunk();
        stats.reference_dispatches = (std::max(lights_.leaf_count(), 1u) + chunk - 1) / chunk;
    }
    if (settings.mode == RenderMode::kRealtime) {
        stats.realtime.cut = settings.realtime_cut;
        stats.realtime.rays = settings.realtime_rays;
        stats.realtime.frames = passes_->realtime().frames_accumulated();
    }
    if (settings.mode == RenderMode::kRestir) stats.realtime.frames = passes_->restir().frames_accumulated();
    if (mode_searches_cuts(settings.mode) && settings.criterion == CutCriterion::kBound) {
        stats.cuts.error_ratio = settings.error_ratio;
        stats.cuts.max_cut_setting = settings.max_cut;
        stats.cuts.bound_search = bound_search_name(settings.bound_search);
        if (settings.bound_search == BoundSearch::kHeap)
            stats.cuts.heap_capacity = passes_->bound_heap().capacity();
        stats.cuts.representatives = representatives_name(settings.representatives);
        stats.cuts.representative_seed = settings.representative_seed;
        if (settings.reconstruction_block > 0) {
            stats.reconstruction.block = settings.reconstruction_block;
            stats.reconstruction.cap = settings.reconstruction_cap;
            stats.reconstruction.bytes = reconstruction_bytes(settings.width, settings.height,
                                                              settings.reconstruction_block,
                                                              settings.reconstruction_cap);
        }
    }
}

// The cut sizes over the regions' pixels: their mean, 99th percentile and the evaluations.
Status Renderer::add_cut_stats(const RenderSettings& settings, std::span<const PixelRegion> regions,
                               RenderStats& stats) const {
    Result<std::vector<uint32_t>> cuts = read_cuts();
    if (!cuts) return make_error(cuts.error());
    uint64_t cut_sum = 0;
    std::vector<uint32_t> geometry_cuts;  // for the percentile: pixels with a cut
    geometry_cuts.reserve(cuts->size() / 2);
    for (const PixelRegion& r : regions) {
        for (uint32_t y = r.y; y < r.y + r.height; ++y) {
            for (uint32_t x = r.x; x < r.x + r.width; ++x) {
                const uint32_t cut = (*cuts)[2 * (size_t(y) * settings.width + x)];
                cut_sum += cut;  // 0 on background
                if (cut > 0) geometry_cuts.push_back(cut);
            }
        }
    }
    if (!geometry_cuts.empty()) {
        const size_t rank = (geometry_cuts.size() * 99) / 100;
        std::nth_element(geometry_cuts.begin(), geometry_cuts.begin() + ptrdiff_t(rank),
                         geometry_cuts.end());
        stats.cuts.cut_p99 = geometry_cuts[rank];
    }
    stats.cuts.avg_cut =
        stats.geometry_pixels > 0 ? double(cut_sum) / double(stats.geometry_pixels) : 0.0;
    stats.cuts.light_evaluations = cut_sum + stats.geometry_pixels * lights_.classic_count();
    return Ok{};
}

Result<PassTimings> Renderer::read_timings() const { return measurements_.read_timings(); }

Result<GpuFrameCounters> Renderer::read_counters() const { return measurements_.read_counters(); }

Result<std::vector<std::byte>> Renderer::read_image(const vk::Image& image) const {
    if (!image) return make_error("nothing has been rendered yet");
    return vk::read_back_image(context_.device(), context_.command_pool(), image,
                               VK_IMAGE_LAYOUT_GENERAL);
}

Result<std::vector<float>> Renderer::read_hdr() const {
    Result<std::vector<std::byte>> bytes = read_image(targets_.hdr);
    if (!bytes) return make_error(bytes.error());
    return reinterpret_texels<float>(*bytes);
}

Result<std::vector<uint8_t>> Renderer::read_display() const {
    Result<std::vector<std::byte>> bytes = read_image(targets_.display);
    if (!bytes) return make_error(bytes.error());
    return reinterpret_texels<uint8_t>(*bytes);
}

Status Renderer::read_clamped_energy(RenderStats& stats) const {
    Result<std::vector<std::byte>> bytes =
        targets_.walk_states.read_back(context_.device(), context_.command_pool());
    if (!bytes) return make_error(bytes.error());
    const size_t pixels = size_t(targets_.width) * targets_.height;
    if (bytes->size() < pixels * sizeof(GpuWalkState))
        return make_error("the walk states hold fewer entries than the image has pixels");
    // Summed in pixel order: the same frame gives the same numbers.
    for (size_t i = 0; i < pixels; ++i) {
        GpuWalkState state;
        std::memcpy(&state, bytes->data() + i * sizeof(GpuWalkState), sizeof(state));
        stats.indirect.energy += double(state.indirect_energy);
        stats.indirect.clamped_energy += double(state.clamped_energy);
        stats.indirect.reference_clamp_change =
            std::max(stats.indirect.reference_clamp_change, double(state.clamp_change));
    }
    return Ok{};
}

Result<std::vector<uint32_t>> Renderer::read_cuts() const {
    Result<std::vector<std::byte>> bytes = read_image(targets_.cut);
    if (!bytes) return make_error(bytes.error());
    return reinterpret_texels<uint32_t>(*bytes);
}

Result<GBufferReadback> Renderer::read_gbuffer() const {
    GBufferReadback g;
    g.eye = targets_.gbuffer_eye;
    g.width = targets_.width;
    g.height = targets_.height;
    std::array<std::pair<const vk::Image*, std::vector<float>*>, 4> planes{
        std::pair{&targets_.position, &g.position}, std::pair{&targets_.normal, &g.normal},
        std::pair{&targets_.albedo, &g.albedo}, std::pair{&targets_.emissive, &g.emissive}};
    for (auto& [image, out] : planes) {
        Result<std::vector<std::byte>> bytes = read_image(*image);
        if (!bytes) return make_error(bytes.error());
        *out = reinterpret_texels<float>(*bytes);
    }
    return g;
}

}  // namespace lc::client
