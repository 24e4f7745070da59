#include "editor_client/render/renderer.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/indirect_clamp.glsl.h"
#include "lightcuts/device/spec_constants.h"
#include "editor_client/render/background.h"
#include "editor_client/render/frame_set_layout.h"
#include "editor_client/render/passes/reference_pass.h"
#include "editor_client/vk/barriers.h"
#include "editor_client/vk/vk_result.h"
#include "protocol/channel_records.h"

namespace lc::client {
namespace {

// Timestamp slots: start, then the end of each pass.
enum Timestamp : uint32_t {
    kTsStart = 0,
    kTsGBuffer = 1,
    kTsLighting = 2,
    kTsOutput = 3,
    kTsCount = 4
};

// One submission's counters added to the frame's.
void add_counters(GpuFrameCounters& sum, const GpuFrameCounters& part) {
    sum.max_cut = std::max(sum.max_cut, part.max_cut);
    sum.nonfinite_pixels += part.nonfinite_pixels;
    sum.geometry_pixels += part.geometry_pixels;
    sum.max_cut_hits += part.max_cut_hits;
    sum.loop_limit_stops += part.loop_limit_stops;
    const uint64_t rays = ((uint64_t(sum.shadow_rays_high) << 32) | sum.shadow_rays) +
                          ((uint64_t(part.shadow_rays_high) << 32) | part.shadow_rays);
    sum.shadow_rays = uint32_t(rays);
    sum.shadow_rays_high = uint32_t(rays >> 32);
}

void add_timings(PassTimings& sum, const PassTimings& part) {
    sum.gbuffer_ms += part.gbuffer_ms;
    sum.lighting_ms += part.lighting_ms;
    sum.output_ms += part.output_ms;
    sum.total_ms += part.total_ms;
}

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
                                                   const LightTree* tree,
                                                   const RendererOptions& options) {
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
        context, renderer->frame_layout_.handle(), renderer->gpu_scene_, scene, options.primary);
    if (!passes) return make_error(passes.error());
    renderer->passes_.emplace(std::move(passes).value());
    renderer->passes_->real_time().set_policy(options.realtime);
    LC_RETURN_IF_ERROR(renderer->set_tree(tree));
    return renderer;
}

Status Renderer::create_frame_resources() {
    VkDevice device = context_.device().handle();
    Result<vk::DescriptorSetLayout> layout = create_frame_set_layout(device);
    if (!layout) return make_error(layout.error());
    frame_layout_ = std::move(layout).value();
    std::array<VkDescriptorPoolSize, 2> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kBindLeafLights},
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                             kFrameBindingCount - kBindLeafLights}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device, 1, sizes);
    if (!pool) return make_error(pool.error());
    frame_pool_ = std::move(pool).value();
    Result<VkDescriptorSet> set = frame_pool_.allocate(frame_layout_);
    if (!set) return make_error(set.error());
    frame_set_ = *set;

    VkDescriptorSetLayout frame_layout = frame_layout_.handle();
    VkPushConstantRange frame_constants{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GpuFrameConstants)};
    Result<vk::PipelineLayout> compute_layout = vk::PipelineLayout::create(
        device, std::span(&frame_layout, 1), std::span(&frame_constants, 1));
    if (!compute_layout) return make_error(compute_layout.error());
    compute_layout_ = std::move(compute_layout).value();

    Result<vk::Buffer> counters =
        vk::Buffer::create(context_.device(), sizeof(GpuFrameCounters),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kHostReadback);
    if (!counters) return make_error(counters.error());
    counters_ = std::move(counters).value();
    LC_RETURN_IF_ERROR(ensure_vpl_visibility(sizeof(GpuVisibilityBits)));

    Result<vk::Buffer> background =
        vk::Buffer::create(context_.device(), sizeof(GpuBackground),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kDeviceLocal);
    if (!background) return make_error(background.error());
    background_ = std::move(background).value();
    const std::vector<GpuEnvironmentTexel> no_texels = environment_texels(nullptr);
    LC_RETURN_IF_ERROR(upload_storage(environment_texels_, std::as_bytes(std::span(no_texels))));

    Result<vk::TimestampQueryPool> timestamps =
        vk::TimestampQueryPool::create(context_.device(), kTsCount);
    if (!timestamps) return make_error(timestamps.error());
    timestamps_ = std::move(timestamps).value();
    return Ok{};
}

Status Renderer::upload_lights(const LightTree* tree) {
    std::vector<GpuLight> leaves;
    std::vector<GpuLight> classic;
    std::vector<GpuTreeNode> nodes;
    for (size_t i = 0; i < scene_.lights.size(); ++i) {
        const SceneLight& light = scene_.lights[i];
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
    if (leaves.size() > UINT32_MAX || nodes.size() > size_t(INT32_MAX) ||
        classic.size() > UINT32_MAX)
        return make_error("too many lights for 32-bit counts");

    LC_RETURN_IF_ERROR(upload_storage(leaf_lights_, std::as_bytes(std::span(leaves))));
    LC_RETURN_IF_ERROR(upload_storage(classic_lights_, std::as_bytes(std::span(classic))));
    LC_RETURN_IF_ERROR(upload_storage(tree_nodes_, std::as_bytes(std::span(nodes))));
    LC_RETURN_IF_ERROR(passes_->real_time().set_tree_nodes(context_.command_pool(), nodes));
    leaf_count_ = uint32_t(leaves.size());
    classic_count_ = uint32_t(classic.size());
    node_count_ = uint32_t(nodes.size());
    return Ok{};
}

Status Renderer::upload_storage(vk::Buffer& out, std::span<const std::byte> bytes) {
    Result<vk::Buffer> buffer = vk::Buffer::create_with_data(
        context_.device(), context_.command_pool(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!buffer) return make_error(buffer.error());
    out = std::move(buffer).value();
    frame_set_dirty_ = true;
    return Ok{};
}

Status Renderer::upload_occluders() {
    shadow_bvh_ = ShadowBvh::build(effects_.occluders, effects_.occluder_masks);
    const ShadowBvhStats& s = shadow_bvh_.stats();
    spdlog::debug(
        "shadow BVH: {} triangles ({} degenerate, {} not casting, {} masked) in {} nodes, "
        "depth {}",
        s.triangles, s.skipped_degenerate, s.skipped_non_casting, s.masked, s.nodes, s.depth);
    LC_RETURN_IF_ERROR(
        upload_storage(bvh_nodes_, std::as_bytes(std::span(shadow_bvh_.gpu_nodes()))));
    LC_RETURN_IF_ERROR(
        upload_storage(masked_triangles_, std::as_bytes(std::span(shadow_bvh_.gpu_masked_triangles()))));
    LC_RETURN_IF_ERROR(upload_storage(alpha_masks_, std::as_bytes(std::span(shadow_bvh_.gpu_alpha_masks()))));
    LC_RETURN_IF_ERROR(upload_storage(mask_texels_, std::as_bytes(std::span(shadow_bvh_.gpu_mask_texels()))));
    return upload_storage(shadow_triangles_,
                          std::as_bytes(std::span(shadow_bvh_.gpu_triangles())));
}

Status Renderer::set_tree(const LightTree* tree) {
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    LC_RETURN_IF_ERROR(upload_lights(tree));
    has_tree_ = tree != nullptr;
    SceneEffects effects = analyse_scene_effects(scene_, tree, options_.shadows, options_.indirect);
    // Which surfaces can hide a light depends on where the lights are; most
    // light edits leave them as they were, and the BVH stays.
    const bool same_occluders = bvh_nodes_ && effects.occluders == effects_.occluders &&
                                effects.occluder_masks == effects_.occluder_masks;
    effects_ = std::move(effects);
    if (!same_occluders) LC_RETURN_IF_ERROR(upload_occluders());
    shadow_bias_ = shadow_ray_bias(scene_);  // the scene's bounds hold its lights
    for (const EffectDecision& d : effects_.decisions)
        spdlog::debug("effect {}: {} ({})", d.name, d.simulated ? "simulated" : "skipped",
                      d.reason);
    // The pipelines are keyed by the effects' specialization constants: a
    // frame after a change finds (or builds) the ones that match.
    passes_->real_time().drop_history();
    return Ok{};
}

Status Renderer::set_environment(std::shared_ptr<const Environment> environment) {
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    const std::vector<GpuEnvironmentTexel> texels = environment_texels(environment.get());
    LC_RETURN_IF_ERROR(upload_storage(environment_texels_, std::as_bytes(std::span(texels))));
    environment_ = std::move(environment);
    passes_->real_time().drop_history();
    return Ok{};
}

GpuBackground Renderer::background(const RenderSettings& settings) const {
    return make_gpu_background(environment_.get(), settings, settings.width, settings.height,
                               scene_.bounds_min, scene_.bounds_max);
}

Status Renderer::validate(const RenderSettings& settings) const {
    ValidationContext context;
    context.has_tree = has_tree_;
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
    work.leaf_count = leaf_count_;
    work.classic_count = classic_count_;
    work.node_count = node_count_;
    work.shadow_bvh = effects_.shadows ? &shadow_bvh_ : nullptr;
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
    frame_set_dirty_ = true;
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
    if (!frame_set_dirty_) return;
    vk::DescriptorWriter(frame_set_)
        .storage_image(kBindPosition, targets_.position.view())
        .storage_image(kBindNormal, targets_.normal.view())
        .storage_image(kBindAlbedo, targets_.albedo.view())
        .storage_image(kBindEmissive, targets_.emissive.view())
        .storage_image(kBindHdr, targets_.hdr.view())
        .storage_image(kBindCut, targets_.cut.view())
        .storage_image(kBindDisplay, targets_.display.view())
        .storage_buffer(kBindLeafLights, leaf_lights_.handle())
        .storage_buffer(kBindTreeNodes, tree_nodes_.handle())
        .storage_buffer(kBindClassicLights, classic_lights_.handle())
        .storage_buffer(kBindCounters, counters_.handle())
        .storage_buffer(kBindBvhNodes, bvh_nodes_.handle())
        .storage_buffer(kBindShadowTriangles, shadow_triangles_.handle())
        .storage_buffer(kBindMaskedTriangles, masked_triangles_.handle())
        .storage_buffer(kBindAlphaMasks, alpha_masks_.handle())
        .storage_buffer(kBindMaskTexels, mask_texels_.handle())
        .storage_buffer(kBindWalkStates, targets_.walk_states.handle())
        .storage_buffer(kBindVplVisibility, vpl_visibility_.handle())
        .storage_buffer(kBindBackground, background_.handle())
        .storage_buffer(kBindEnvironmentTexels, environment_texels_.handle())
        .update(context_.device().handle());
    frame_set_dirty_ = false;
}

Frame Renderer::make_frame(const RenderSettings& settings) const {
    Frame frame;
    frame.settings = &settings;
    frame.targets = &targets_;
    frame.effects = &effects_;
    frame.shadows = traces_shadows();
    frame.alpha_masks = frame.shadows && shadow_bvh_.stats().masked > 0;
    frame.workgroup_size = options_.workgroup_size;
    frame.compute_layout = compute_layout_.handle();
    frame.frame_set = frame_set_;
    frame.reference_chunk = reference_chunk();
    GpuFrameConstants& constants = frame.constants;
    constants.width = targets_.width;
    constants.height = targets_.height;
    constants.leaf_count = leaf_count_;
    constants.classic_count = classic_count_;
    constants.node_count = node_count_;
    constants.exposure = settings.exposure;
    constants.scale_bar_rows =
        settings.mode == RenderMode::kCutSize ? std::min(kScaleBarRows, targets_.height / 4) : 0u;
    constants.shadow_bias = frame.shadows ? shadow_bias_ : 0.0f;
    constants.bvh_node_count = frame.shadows ? uint32_t(shadow_bvh_.gpu_nodes().size()) : 0u;
    constants.light_begin = 0;
    constants.light_end = leaf_count_;
    constants.eye = settings.camera.eye;
    constants.clamp_passes = reference_clamp_passes(settings);
    constants.vpl_visibility_stride = constants.clamp_passes > 0 ? vpl_visibility_stride_ : 0u;
    return frame;
}

Status Renderer::ensure_vpl_visibility(uint64_t bytes) {
    if (vpl_visibility_ && vpl_visibility_.size() >= bytes) return Ok{};
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    Result<vk::Buffer> buffer =
        vk::Buffer::create(context_.device(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kDeviceLocal);
    if (!buffer) return make_error("kept visibility: " + buffer.error());
    vpl_visibility_ = std::move(buffer).value();
    frame_set_dirty_ = true;
    return Ok{};
}

// The exact clamp's kept visibility for a frame with these settings: one bit
// per pixel and leaf, within the budget (else Newton's passes trace again).
Status Renderer::prepare_vpl_visibility(const RenderSettings& settings) {
    vpl_visibility_stride_ = 0;
    if (reference_clamp_passes(settings) == 0 || !traces_shadows()) return Ok{};
    const uint64_t stride = (uint64_t(leaf_count_) + 127) / 128;
    const uint64_t bytes = uint64_t(settings.width) * settings.height * stride * sizeof(GpuVisibilityBits);
    if (bytes > options_.vpl_visibility_budget_bytes) return Ok{};
    LC_RETURN_IF_ERROR(ensure_vpl_visibility(bytes));
    vpl_visibility_stride_ = uint32_t(stride);
    return Ok{};
}

Result<std::array<FramePass*, 3>> Renderer::prepare_passes(const Frame& frame) {
    return passes_->prepare(pipelines_, frame);
}

Result<std::array<FramePass*, 3>> Renderer::prepare_regions(Frame& frame,
                                                            std::span<const PixelRegion> regions,
                                                            bool continues_image) {
    update_frame_descriptors();
    frame.regions = regions;
    frame.continues_image = continues_image;
    return prepare_passes(frame);
}

Status Renderer::record(VkCommandBuffer cmd, const RenderSettings& settings) {
    const PixelRegion whole{0, 0, settings.width, settings.height};
    return record_regions(cmd, settings, std::span(&whole, 1), false);
}

Status Renderer::record_regions(VkCommandBuffer cmd, const RenderSettings& settings,
                                std::span<const PixelRegion> regions, bool continues_image) {
    return record_frame(cmd, settings, regions, continues_image, DispatchRange{});
}

Status Renderer::record_frame(VkCommandBuffer cmd, const RenderSettings& settings,
                              std::span<const PixelRegion> regions, bool continues_image,
                              DispatchRange reference_dispatches) {
    LC_RETURN_IF_ERROR(validate(settings));
    LC_RETURN_IF_ERROR(check_regions(regions, settings.width, settings.height));
    Result<bool> remade = ensure_targets(settings.width, settings.height);
    if (!remade) return make_error(remade.error());
    if (*remade && continues_image)
        return make_error("the image to continue was lost: another size was rendered since");
    if (!continues_image) LC_RETURN_IF_ERROR(prepare_vpl_visibility(settings));
    Frame frame = make_frame(settings);
    frame.reference_dispatches = reference_dispatches;
    Result<std::array<FramePass*, 3>> passes = prepare_regions(frame, regions, continues_image);
    if (!passes) return make_error(passes.error());
    last_eye_ = settings.camera.eye;

    timestamps_.reset(cmd);
    timestamps_.write(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, kTsStart);
    vkCmdFillBuffer(cmd, counters_.handle(), 0, VK_WHOLE_SIZE, 0);
    const GpuBackground background = this->background(settings);
    vkCmdUpdateBuffer(cmd, background_.handle(), 0, sizeof(background), &background);
    // The clamp's per-pixel statistics: background pixels keep their zeros. Only
    // when an image starts: a continued one (the next submission of a reference,
    // the next tiles of a progressive view) carries its sums in the walk states.
    if (effects_.indirect_clamp && !continues_image)
        vkCmdFillBuffer(cmd, targets_.walk_states.handle(), 0, VK_WHOLE_SIZE, 0);
    if (frame.constants.vpl_visibility_stride > 0 && !continues_image)
        vkCmdFillBuffer(cmd, vpl_visibility_.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       kComputeStage, kStorageReadWrite);
    uint32_t slot = kTsStart;
    for (const FramePass* pass : *passes) {
        // A continued image keeps its G-buffer: the pass's time slot stays, empty.
        const bool skipped = continues_image && pass == passes->front();
        if (!skipped) pass->record(cmd, frame);
        timestamps_.write(cmd, pass->last_stage(), ++slot);
    }
    if (settings.mode == RenderMode::kRealTime) passes_->real_time().advance();

    // Results become readable by copies (read-backs, blits) and by the host (counters).
    vk::memory_barrier(cmd, kComputeStage, kStorageWrite,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
    return Ok{};
}

Status Renderer::render_gbuffer(const RenderSettings& settings) {
    LC_RETURN_IF_ERROR(validate(settings));
    LC_RETURN_IF_ERROR(ensure_targets(settings.width, settings.height));
    update_frame_descriptors();
    const Frame frame = make_frame(settings);
    FramePass& gbuffer = passes_->gbuffer();
    LC_RETURN_IF_ERROR(gbuffer.prepare(pipelines_, frame));
    last_eye_ = settings.camera.eye;
    return context_.command_pool().run_one_time(context_.device(), [&](VkCommandBuffer cmd) {
        gbuffer.record(cmd, frame);
        vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | kComputeStage,
                           VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                           VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    });
}

Status Renderer::record_output(VkCommandBuffer cmd, const RenderSettings& settings,
                               std::span<const PixelRegion> regions) {
    LC_RETURN_IF_ERROR(validate(settings));
    LC_RETURN_IF_ERROR(check_regions(regions, settings.width, settings.height));
    if (targets_.width != settings.width || targets_.height != settings.height)
        return make_error("no lit image of this size to tone-map again");
    Frame frame = make_frame(settings);
    Result<std::array<FramePass*, 3>> passes = prepare_regions(frame, regions, true);
    if (!passes) return make_error(passes.error());
    passes->back()->record(cmd, frame);
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
    LC_RETURN_IF_ERROR(validate(settings));
    LC_RETURN_IF_ERROR(check_regions(regions, settings.width, settings.height));
    // Build targets and pipelines before the clock starts: wall_ms is the frame.
    if (Result<bool> remade = ensure_targets(settings.width, settings.height); !remade)
        return make_error(remade.error());
    if (auto passes = prepare_passes(make_frame(settings)); !passes)
        return make_error(passes.error());

    std::vector<DispatchRange> submissions{DispatchRange{}};
    if (settings.mode == RenderMode::kReference) {
        Frame frame = make_frame(settings);
        frame.regions = regions;
        submissions =
            reference_submissions(frame, options_.reference_evaluations_per_submission);
    }

    auto start = std::chrono::steady_clock::now();
    PassTimings timings;
    GpuFrameCounters counters;
    for (size_t s = 0; s < submissions.size(); ++s) {
        Status recorded = Ok{};
        LC_RETURN_IF_ERROR(context_.command_pool().run_one_time(
            context_.device(), [&](VkCommandBuffer cmd) {
                recorded = record_frame(cmd, settings, regions, s > 0, submissions[s]);
            }));
        LC_RETURN_IF_ERROR(recorded);
        Result<PassTimings> part_timings = read_timings();
        if (!part_timings) return make_error(part_timings.error());
        add_timings(timings, *part_timings);
        Result<GpuFrameCounters> part_counters = read_counters();
        if (!part_counters) return make_error(part_counters.error());
        add_counters(counters, *part_counters);
    }
    double wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    RenderStats stats;
    stats.mode = render_mode_name(settings.mode);
    stats.criterion = mode_searches_cuts(settings.mode) ? criterion_name(settings.criterion)
                      : settings.mode == RenderMode::kRealTime ? "stochastic"
                                                               : "none";
    stats.device = context_.physical().name();
    stats.width = settings.width;
    stats.height = settings.height;
    stats.lights = uint64_t(leaf_count_) + classic_count_;
    stats.tree_lights = has_tree_ ? leaf_count_ : 0;
    stats.classic_lights = classic_count_;
    stats.nodes = node_count_;
    stats.tree_depth = tree_depth_;
    stats.wall_ms = wall_ms;
    stats.submissions = uint32_t(submissions.size());

    stats.render_ms = timings.total_ms;
    stats.gbuffer_ms = timings.gbuffer_ms;
    stats.primary = primary_visibility_name(passes_->primary());
    stats.lighting_ms = timings.lighting_ms;
    stats.output_ms = timings.output_ms;

    stats.max_cut = counters.max_cut;
    stats.geometry_pixels = counters.geometry_pixels;
    stats.nonfinite_pixels = counters.nonfinite_pixels;
    stats.max_cut_hits = counters.max_cut_hits;
    stats.loop_limit_stops = counters.loop_limit_stops;
    stats.shadows = traces_shadows();
    stats.shadow_rays = (uint64_t(counters.shadow_rays_high) << 32) | counters.shadow_rays;
    stats.shadow_triangles = shadow_bvh_.stats().triangles;
    stats.shadow_bvh_nodes = shadow_bvh_.stats().nodes;
    if (effects_.indirect_lights > 0) {
        stats.indirect = effects_.indirect_off ? "off" : "on";
        stats.indirect_lights = effects_.indirect_lights;
        stats.indirect_patches = effects_.indirect_patches;
    }
    if (effects_.indirect_clamp) LC_RETURN_IF_ERROR(read_clamped_energy(stats));
    stats.reference_clamp_passes = reference_clamp_passes(settings);
    stats.reference_visibility_kept = stats.reference_clamp_passes > 0 && vpl_visibility_stride_ > 0;
    if (settings.mode == RenderMode::kReference) {
        const uint32_t chunk = reference_chunk();
        stats.reference_dispatches = (std::max(leaf_count_, 1u) + chunk - 1) / chunk;
    }
    if (settings.mode == RenderMode::kRealTime) {
        stats.realtime_cut = settings.realtime_cut;
        stats.realtime_frames = passes_->real_time().frames_accumulated();
    }
    if (mode_searches_cuts(settings.mode) && settings.criterion == CutCriterion::kBound) {
        stats.error_ratio = settings.error_ratio;
        stats.max_cut_setting = settings.max_cut;
        stats.bound_search = bound_search_name(settings.bound_search);
        if (settings.bound_search == BoundSearch::kHeap) stats.heap_capacity = passes_->bound_heap().capacity();
        stats.representatives = representatives_name(settings.representatives);
        stats.representative_seed = settings.representative_seed;
    }

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
        stats.cut_p99 = geometry_cuts[rank];
    }
    stats.avg_cut =
        stats.geometry_pixels > 0 ? double(cut_sum) / double(stats.geometry_pixels) : 0.0;
    stats.light_evaluations = cut_sum + stats.geometry_pixels * classic_count_;

    stats.effects_simulated = effects_.simulated();
    stats.effects_skipped = effects_.skipped();
    stats.validation_messages = context_.validation_message_count();
    stats.validation_enabled = context_.validation_enabled();
    return stats;
}

Result<PassTimings> Renderer::read_timings() const {
    Result<std::vector<double>> ms = timestamps_.read_ms();
    if (!ms) return make_error(ms.error());
    PassTimings t;
    t.gbuffer_ms = (*ms)[kTsGBuffer] - (*ms)[kTsStart];
    t.lighting_ms = (*ms)[kTsLighting] - (*ms)[kTsGBuffer];
    t.output_ms = (*ms)[kTsOutput] - (*ms)[kTsLighting];
    t.total_ms = (*ms)[kTsOutput] - (*ms)[kTsStart];
    return t;
}

Result<GpuFrameCounters> Renderer::read_counters() const {
    GpuFrameCounters counters;
    std::memcpy(&counters, counters_.mapped(), sizeof(counters));
    return counters;
}

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
        stats.indirect_energy += double(state.indirect_energy);
        stats.clamped_energy += double(state.clamped_energy);
        stats.reference_clamp_change = std::max(stats.reference_clamp_change, double(state.clamp_change));
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
    g.eye = last_eye_;
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
