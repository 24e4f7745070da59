#include "editor_client/render/renderer.h"

#include <spdlog/spdlog.h>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>

#include "lightcuts/bound_walk.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/limits.h"
#include "lightcuts/device/spec_constants.h"
#include "editor_client/vk/barriers.h"
#include "lightcuts/status_macros.h"
#include "protocol/channel_records.h"

// SPIR-V generated from shaders/ at build time.
#include "cut_view_comp.spv.h"
#include "gbuffer_frag.spv.h"
#include "gbuffer_vert.spv.h"
#include "lightcuts_bound_heap_comp.spv.h"
#include "lightcuts_bound_walk_comp.spv.h"
#include "lightcuts_radius_comp.spv.h"
#include "reference_comp.spv.h"
#include "tone_map_comp.spv.h"

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

template <size_t N>
std::span<const uint32_t> spirv(const uint32_t (&words)[N]) {
    return std::span<const uint32_t>(words, N);
}

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kStorageWrite = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
constexpr VkAccessFlags2 kStorageReadWrite =
    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

template <typename T>
std::vector<T> reinterpret_texels(const std::vector<std::byte>& bytes) {
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    return out;
}

}  // namespace

glm::mat4 view_projection(const RenderCamera& camera, float aspect, const glm::vec3& bounds_min,
                          const glm::vec3& bounds_max) {
    glm::vec3 forward = camera.target - camera.eye;
    glm::vec3 up = camera.up;
    // A view straight along `up` has no roll reference: borrow another axis.
    if (glm::length(glm::cross(glm::normalize(forward), glm::normalize(up))) < 1e-4f)
        up = std::abs(forward.y) > std::abs(forward.z) ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    glm::mat4 view = glm::lookAtRH(camera.eye, camera.target, up);

    glm::vec3 center = 0.5f * (bounds_min + bounds_max);
    float radius = 0.5f * glm::length(bounds_max - bounds_min);
    float distance = glm::length(center - camera.eye);
    float far_plane = std::max(distance + radius, 1e-3f) * 1.01f;
    float near_plane = std::max(distance - radius, far_plane * 1e-5f);
    glm::mat4 projection = glm::perspectiveRH_ZO(camera.yfov, aspect, near_plane, far_plane);
    projection[1][1] *= -1.0f;  // Vulkan's clip space has y pointing down
    return projection * view;
}

Renderer::Renderer(const vk::Context& context, const Scene& scene, const RendererOptions& options)
    : context_(context), scene_(scene), options_(options) {}

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
    LC_RETURN_IF_ERROR(renderer->set_tree(tree));
    return renderer;
}

Status Renderer::create_frame_resources() {
    VkDevice device = context_.device().handle();
    std::array<VkDescriptorSetLayoutBinding, kFrameBindingCount> bindings{};
    for (uint32_t b = 0; b < kFrameBindingCount; ++b) {
        bindings[b].binding = b;
        bindings[b].descriptorType = b < kBindLeafLights ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                                         : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[b].descriptorCount = 1;
        bindings[b].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    Result<vk::DescriptorSetLayout> layout = vk::DescriptorSetLayout::create(device, bindings);
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

    VkDescriptorSetLayout material_layout = gpu_scene_.material_layout().handle();
    VkPushConstantRange draw_constants{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                       sizeof(GpuDrawConstants)};
    Result<vk::PipelineLayout> gbuffer_layout = vk::PipelineLayout::create(
        device, std::span(&material_layout, 1), std::span(&draw_constants, 1));
    if (!gbuffer_layout) return make_error(gbuffer_layout.error());
    gbuffer_layout_ = std::move(gbuffer_layout).value();

    Result<vk::Buffer> counters =
        vk::Buffer::create(context_.device(), sizeof(GpuFrameCounters),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kHostReadback);
    if (!counters) return make_error(counters.error());
    counters_ = std::move(counters).value();

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
    shadow_bvh_ = ShadowBvh::build(effects_.occluders);
    const ShadowBvhStats& s = shadow_bvh_.stats();
    spdlog::debug("shadow BVH: {} triangles ({} degenerate, {} not casting) in {} nodes, depth {}",
                  s.triangles, s.skipped_degenerate, s.skipped_non_casting, s.nodes, s.depth);
    LC_RETURN_IF_ERROR(
        upload_storage(bvh_nodes_, std::as_bytes(std::span(shadow_bvh_.gpu_nodes()))));
    return upload_storage(shadow_triangles_,
                          std::as_bytes(std::span(shadow_bvh_.gpu_triangles())));
}

Status Renderer::set_tree(const LightTree* tree) {
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    LC_RETURN_IF_ERROR(upload_lights(tree));
    has_tree_ = tree != nullptr;
    SceneEffects effects = analyse_scene_effects(scene_, tree, options_.shadows);
    // Which surfaces can hide a light depends on where the lights are; most
    // light edits leave them as they were, and the BVH stays.
    const bool same_occluders = bvh_nodes_ && effects.occluders == effects_.occluders;
    effects_ = std::move(effects);
    if (!same_occluders) LC_RETURN_IF_ERROR(upload_occluders());
    shadow_bias_ = shadow_ray_bias(scene_);  // the scene's bounds hold its lights
    for (const EffectDecision& d : effects_.decisions)
        spdlog::debug("effect {}: {} ({})", d.name, d.simulated ? "simulated" : "skipped",
                      d.reason);
    // Specialization constants changed: rebuild pipelines on next use.
    gbuffer_pipeline_.reset();
    reference_pipeline_.reset();
    lightcuts_pipeline_.reset();
    tone_map_pipeline_.reset();
    cuts_view_pipeline_.reset();
    cut_size_view_pipeline_.reset();
    return Ok{};
}

Status Renderer::validate(const RenderSettings& settings) const {
    if (settings.width == 0 || settings.height == 0 || settings.width > 16384 ||
        settings.height > 16384)
        return make_error("image size " + std::to_string(settings.width) + "x" +
                          std::to_string(settings.height) + " is outside 1x1 .. 16384x16384");
    if (mode_needs_tree(settings.mode) && !has_tree_)
        return make_error(std::string("mode '") + render_mode_name(settings.mode) +
                          "' needs a light tree (--tree, --server or --spawn-server)");
    if (settings.criterion != CutCriterion::kRadius && settings.criterion != CutCriterion::kBound)
        return make_error("unknown cut criterion " +
                          std::to_string(static_cast<int>(settings.criterion)));
    if (!std::isfinite(settings.error_ratio) || settings.error_ratio < 0.0f)
        return make_error("the error ratio must be a finite number >= 0");
    if (settings.max_cut < 1 || settings.max_cut > kMaxGpuCut)
        return make_error("max cut " + std::to_string(settings.max_cut) + " is outside 1 .. " +
                          std::to_string(kMaxGpuCut));
    const RenderCamera& c = settings.camera;
    if (!finite(c.eye) || !finite(c.target) || !finite(c.up) || !std::isfinite(c.yfov) ||
        !(c.yfov > 0.0f && c.yfov < 3.14f))
        return make_error("the camera has non-finite values or a field of view outside (0, 180)");
    if (glm::length(c.target - c.eye) <= 0.0f)
        return make_error("the camera's eye and target coincide");
    if (!std::isfinite(settings.exposure) || settings.exposure < 0.0f)
        return make_error("exposure must be a finite number >= 0");
    return check_loop_budget(settings);
}

namespace {
constexpr uint64_t kLoopBudget = 65535;

// Worst-case loop iterations of one shadow ray: every BVH node once.
uint64_t shadow_ray_iterations(bool shadows, const ShadowBvh& bvh) {
    if (!shadows || bvh.empty()) return 0;
    return (uint64_t(bvh.gpu_nodes().size()) + kShadowUnroll - 1) / kShadowUnroll + 1;
}

// The classic lights' loop, with a ray per light (`ray` iterations each).
uint64_t classic_iterations(uint32_t classic_count, uint64_t ray) {
    return (uint64_t(classic_count) + kLoopUnroll - 1) / kLoopUnroll + 1 +
           uint64_t(classic_count) * ray;
}

bool has_loop_limit(const vk::Context& context) {
    return context.physical().name().find("llvmpipe") != std::string::npos;
}
}  // namespace

uint32_t Renderer::reference_chunk() const {
    const uint32_t all = std::max(leaf_count_, 1u);
    if (!has_loop_limit(context_)) return all;
    const uint64_t ray = shadow_ray_iterations(effects_.shadows, shadow_bvh_);
    const uint64_t classic = classic_iterations(classic_count_, ray);
    // Per group of kLoopUnroll leaves: one iteration and their rays; the
    // remainder loop may add kLoopUnroll - 1 single leaves.
    const uint64_t per_group = 1 + kLoopUnroll * ray;
    const uint64_t tail = (kLoopUnroll - 1) * (1 + ray) + 2;
    if (classic + tail + per_group > kLoopBudget) return kLoopUnroll;  // refused by the check
    const uint64_t groups = (kLoopBudget - classic - tail) / per_group;
    return uint32_t(std::min<uint64_t>(all, groups * kLoopUnroll));
}

// llvmpipe stops an invocation's loops after 65,535 iterations in total, and
// says nothing (lightcuts/device/limits.h). Reference mode splits its leaves
// over dispatches that each fit (reference_chunk); shadow rays and the bound
// walk notice a walk the limit cut short and count it (loop_limit_stops);
// other work that could exceed the budget is refused here with the reason,
// never rendered truncated. Other devices have no such limit.
Status Renderer::check_loop_budget(const RenderSettings& settings) const {
    if (!has_loop_limit(context_)) return Ok{};
    const uint64_t ray = shadow_ray_iterations(effects_.shadows, shadow_bvh_);
    uint64_t iterations = classic_iterations(classic_count_, ray);
    std::string what;
    if (settings.mode == RenderMode::kReference) {
        // Without tree lights the leaf loops trace no ray: a scene without
        // lights renders its emission (or black), however large its BVH.
        const uint64_t leaf_ray = leaf_count_ > 0 ? ray : 0;
        iterations += 1 + kLoopUnroll * leaf_ray + (kLoopUnroll - 1) * (1 + leaf_ray) + 2;
        what = std::to_string(classic_count_) + " classic lights" +
               (ray > 0 ? " with shadow rays" : "") + " in reference mode";
    } else if (settings.criterion == CutCriterion::kRadius) {
        iterations += (uint64_t(node_count_) + kRadiusUnroll - 1) / kRadiusUnroll + 1;
        what = "a radius-criterion walk of " + std::to_string(node_count_) + " nodes";
    } else if (settings.bound_search == BoundSearch::kWalk) {
        // A pass the limit cut short (its walk did not reach the end of the
        // tree, or a ray did not finish) runs again in the next dispatch; one
        // that alone exceeds the limit is discarded, the pixel keeping its
        // last complete pass and counted in loop_limit_stops: nothing is
        // truncated silently, so nothing to refuse.
        return Ok{};
    } else {
        // Per refinement: a heap pop and two pushes (log2 K each), two children
        // with an 8-corner bound each; then the final sum over the heap.
        uint64_t k = settings.max_cut, log_k = 1;
        while ((uint64_t(1) << log_k) < k + 1) ++log_k;
        iterations += k * (3 * log_k + 2 * 8 + 4) + k;
        what = "the bound criterion with max cut " + std::to_string(settings.max_cut);
    }
    if (iterations <= kLoopBudget) return Ok{};
    return make_error(what + " needs about " + std::to_string(iterations) +
                      " shader loop iterations per pixel; llvmpipe (lavapipe) silently stops loops after " +
                      std::to_string(kLoopBudget) +
                      ", so this render is refused rather than truncated: use fewer lights, a smaller "
                      "--max-cut, the bound criterion, or a GPU");
}

Status Renderer::ensure_targets(uint32_t width, uint32_t height) {
    if (targets_.width == width && targets_.height == height) return Ok{};
    LC_RETURN_IF_ERROR(context_.device().wait_idle());
    Result<RenderTargets> targets = RenderTargets::create(context_.device(), width, height);
    if (!targets) return make_error(targets.error());
    targets_ = std::move(targets).value();
    frame_set_dirty_ = true;
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
        .storage_buffer(kBindWalkStates, targets_.walk_states.handle())
        .update(context_.device().handle());
    frame_set_dirty_ = false;
}

Result<VkPipeline> Renderer::gbuffer_pipeline() {
    if (!gbuffer_pipeline_) {
        vk::Specialization fragment;
        fragment.set_bool(kSpecTextures, effects_.textures);
        vk::GraphicsPipelineDesc desc;
        desc.layout = gbuffer_layout_.handle();
        desc.vertex_spirv = spirv(gbuffer_vert_spv);
        desc.fragment_spirv = spirv(gbuffer_frag_spv);
        desc.fragment_specialization = &fragment;
        desc.vertex_bindings = {{0, sizeof(GpuVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
        desc.vertex_attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, position)},
                                  {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, normal)},
                                  {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(GpuVertex, uv)}};
        desc.color_formats = {kGBufferFormat, kGBufferFormat, kGBufferFormat, kGBufferFormat};
        desc.depth_format = kDepthFormat;
        desc.cull_mode = VK_CULL_MODE_NONE;  // surfaces are lit on the side the camera sees
        Result<vk::GraphicsPipeline> pipeline =
            vk::GraphicsPipeline::create(context_.device().handle(), desc);
        if (!pipeline) return make_error("G-buffer pipeline: " + pipeline.error());
        gbuffer_pipeline_ = std::move(pipeline).value();
    }
    return gbuffer_pipeline_->handle();
}

Result<VkPipeline> Renderer::lighting_pipeline(const RenderSettings& settings) {
    const RenderMode mode = settings.mode;
    std::optional<vk::ComputePipeline>& slot =
        mode == RenderMode::kReference ? reference_pipeline_ : lightcuts_pipeline_;
    // The cut settings are specialization constants: a change rebuilds the pipeline.
    const bool bound = settings.criterion == CutCriterion::kBound;
    const LightcutsPipelineKey key{settings.criterion, bound ? settings.error_ratio : 0.0f,
                                   bound ? settings.max_cut : 0u,
                                   bound ? settings.bound_search : BoundSearch::kWalk};
    if (mode != RenderMode::kReference && slot && !(lightcuts_key_ == key)) slot.reset();
    if (!slot) {
        vk::Specialization spec;
        spec.set_uint(kSpecWorkgroupX, options_.workgroup_size)
            .set_uint(kSpecWorkgroupY, options_.workgroup_size)
            .set_bool(kSpecPointLights, effects_.point_lights)
            .set_bool(kSpecSpotLights, effects_.spot_lights)
            .set_bool(kSpecDirectionalLights, effects_.directional_lights)
            .set_bool(kSpecRangeWindow, effects_.range_window)
            .set_bool(kSpecClassicLights, effects_.classic_lights)
            .set_bool(kSpecEmissive, effects_.emissive)
            .set_bool(kSpecShadows, traces_shadows())
            .set_bool(kSpecSpecular, effects_.specular);
        if (mode != RenderMode::kReference) {
            // The heap needs room for one refinement (two children) even at
            // max-cut 1; the walk keeps no heap, so its array stays minimal.
            const bool heap = settings.bound_search == BoundSearch::kHeap;
            spec.set_uint(kSpecErrorRatio, std::bit_cast<uint32_t>(settings.error_ratio))
                .set_uint(kSpecMaxCut, heap ? std::max(settings.max_cut, 2u) : 2u)
                .set_uint(kSpecWalkMaxCut, settings.max_cut)
                .set_uint(kSpecWalkMaxPasses, kWalkMaxPasses)
                .set_uint(kSpecWalkShrink, std::bit_cast<uint32_t>(kWalkShrink))
                .set_uint(kSpecWalkMargin, std::bit_cast<uint32_t>(kWalkMargin))
                .set_uint(kSpecWalkBisections, kWalkBisections);
            lightcuts_key_ = key;
        }
        // One module per cut search (shaders/lightcuts_*.comp).
        std::span<const uint32_t> code = spirv(reference_comp_spv);
        if (mode != RenderMode::kReference)
            code = !bound                                       ? spirv(lightcuts_radius_comp_spv)
                   : settings.bound_search == BoundSearch::kHeap ? spirv(lightcuts_bound_heap_comp_spv)
                                                                 : spirv(lightcuts_bound_walk_comp_spv);
        Result<vk::ComputePipeline> pipeline = vk::ComputePipeline::create(
            context_.device().handle(), compute_layout_.handle(), code, spec);
        if (!pipeline) return make_error("lighting pipeline: " + pipeline.error());
        slot = std::move(pipeline).value();
    }
    return slot->handle();
}

Result<VkPipeline> Renderer::output_pipeline(RenderMode mode) {
    std::optional<vk::ComputePipeline>& slot = mode == RenderMode::kCuts ? cuts_view_pipeline_
                                               : mode == RenderMode::kCutSize
                                                   ? cut_size_view_pipeline_
                                                   : tone_map_pipeline_;
    if (!slot) {
        vk::Specialization spec;
        spec.set_uint(kSpecWorkgroupX, options_.workgroup_size)
            .set_uint(kSpecWorkgroupY, options_.workgroup_size);
        std::span<const uint32_t> code = spirv(tone_map_comp_spv);
        if (mode == RenderMode::kCuts || mode == RenderMode::kCutSize) {
            spec.set_uint(kSpecCutView, mode == RenderMode::kCuts ? kCutViewCuts : kCutViewCutSize);
            code = spirv(cut_view_comp_spv);
        }
        Result<vk::ComputePipeline> pipeline = vk::ComputePipeline::create(
            context_.device().handle(), compute_layout_.handle(), code, spec);
        if (!pipeline) return make_error("output pipeline: " + pipeline.error());
        slot = std::move(pipeline).value();
    }
    return slot->handle();
}

void Renderer::record_gbuffer_pass(VkCommandBuffer cmd, VkPipeline pipeline,
                                   const RenderSettings& settings) {
    const std::array<const vk::Image*, 4> colors{&targets_.position, &targets_.normal,
                                                 &targets_.albedo, &targets_.emissive};
    for (const vk::Image* image : colors) {
        vk::transition_image(cmd, {image->handle(), VK_IMAGE_LAYOUT_UNDEFINED,
                                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kCompute,
                                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                                   VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                   VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT});
    }
    vk::transition_image(
        cmd, {targets_.depth.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
              VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
              VK_IMAGE_ASPECT_DEPTH_BIT});

    std::array<VkRenderingAttachmentInfo, 4> color_attachments{};
    for (size_t i = 0; i < colors.size(); ++i) {
        VkRenderingAttachmentInfo& a = color_attachments[i];
        a = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = colors[i]->view();
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // w = 0 marks background
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        a.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = targets_.depth.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {targets_.width, targets_.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = uint32_t(color_attachments.size());
    rendering.pColorAttachments = color_attachments.data();
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);

    VkViewport viewport{0.0f, 0.0f, float(targets_.width), float(targets_.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {targets_.width, targets_.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    if (!gpu_scene_.draws().empty()) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        VkBuffer vertex_buffer = gpu_scene_.vertex_buffer();
        VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
        vkCmdBindIndexBuffer(cmd, gpu_scene_.index_buffer(), 0, VK_INDEX_TYPE_UINT32);
        GpuDrawConstants constants;
        constants.view_proj =
            view_projection(settings.camera, float(targets_.width) / float(targets_.height),
                            scene_.bounds_min, scene_.bounds_max);
        constants.eye_roughness = glm::vec4(settings.camera.eye, 0.0f);
        for (const GpuDraw& draw : gpu_scene_.draws()) {
            const GpuMaterial& material = gpu_scene_.materials()[draw.material];
            constants.base_color_factor = material.base_color_factor;
            constants.emissive_metallic = glm::vec4(material.emissive_factor, material.metallic);
            constants.eye_roughness.w = material.roughness;
            constants.flags = material.flags;
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, gbuffer_layout_.handle(),
                                    0, 1, &material.set, 0, nullptr);
            vkCmdPushConstants(cmd, gbuffer_layout_.handle(),
                               VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(constants), &constants);
            vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, draw.vertex_offset, 0);
        }
    }
    vkCmdEndRendering(cmd);

    for (const vk::Image* image : colors) {
        vk::transition_image(
            cmd, {image->handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, kCompute,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT});
    }
}

Status Renderer::record(VkCommandBuffer cmd, const RenderSettings& settings) {
    LC_RETURN_IF_ERROR(validate(settings));
    LC_RETURN_IF_ERROR(ensure_targets(settings.width, settings.height));
    Result<VkPipeline> gbuffer = gbuffer_pipeline();
    if (!gbuffer) return make_error(gbuffer.error());
    Result<VkPipeline> lighting = lighting_pipeline(settings);
    if (!lighting) return make_error(lighting.error());
    Result<VkPipeline> output = output_pipeline(settings.mode);
    if (!output) return make_error(output.error());
    update_frame_descriptors();

    timestamps_.reset(cmd);
    timestamps_.write(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, kTsStart);
    vkCmdFillBuffer(cmd, counters_.handle(), 0, VK_WHOLE_SIZE, 0);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       kCompute, kStorageReadWrite);

    record_gbuffer_pass(cmd, *gbuffer, settings);
    timestamps_.write(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, kTsGBuffer);

    // Lighting: every pixel of hdr and cut is written, so old contents are dropped.
    for (const vk::Image* image : {&targets_.hdr, &targets_.cut}) {
        vk::transition_image(
            cmd, {image->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, kCompute,
                  kStorageReadWrite, kCompute, kStorageWrite});
    }
    GpuFrameConstants constants;
    constants.width = targets_.width;
    constants.height = targets_.height;
    constants.leaf_count = leaf_count_;
    constants.classic_count = classic_count_;
    constants.node_count = node_count_;
    constants.exposure = settings.exposure;
    constants.scale_bar_rows =
        settings.mode == RenderMode::kCutSize ? std::min(kScaleBarRows, targets_.height / 4) : 0u;
    const bool shadows = traces_shadows();
    constants.shadow_bias = shadows ? shadow_bias_ : 0.0f;
    constants.bvh_node_count = shadows ? uint32_t(shadow_bvh_.gpu_nodes().size()) : 0u;
    constants.light_begin = 0;
    constants.light_end = leaf_count_;
    constants.eye = settings.camera.eye;
    last_eye_ = settings.camera.eye;
    const uint32_t groups_x =
        (targets_.width + options_.workgroup_size - 1) / options_.workgroup_size;
    const uint32_t groups_y =
        (targets_.height + options_.workgroup_size - 1) / options_.workgroup_size;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compute_layout_.handle(), 0, 1,
                            &frame_set_, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, *lighting);
    if (settings.mode == RenderMode::kReference) {
        // Each dispatch adds its leaves to the previous dispatches' sums.
        const uint32_t chunk = reference_chunk();
        uint32_t begin = 0;
        do {
            constants.light_begin = begin;
            constants.light_end = leaf_count_ - begin > chunk ? begin + chunk : leaf_count_;
            if (begin > 0)
                vk::memory_barrier(cmd, kCompute, kStorageReadWrite, kCompute, kStorageReadWrite);
            vkCmdPushConstants(cmd, compute_layout_.handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                               sizeof(constants), &constants);
            vkCmdDispatch(cmd, groups_x, groups_y, 1);
            begin = constants.light_end;
        } while (begin < leaf_count_);
    } else if (settings.criterion == CutCriterion::kBound &&
               settings.bound_search == BoundSearch::kWalk) {
        // A pass that llvmpipe's loop limit cuts short runs again in the
        // next dispatch (the search kept in walk_states); every dispatch
        // completes a pass or ends the search, so kWalkMaxPasses of them end
        // every search. Pixels that are done return at once.
        for (uint32_t dispatch = 0; dispatch < kWalkMaxPasses; ++dispatch) {
            constants.walk_dispatch = dispatch;
            if (dispatch > 0)
                vk::memory_barrier(cmd, kCompute, kStorageReadWrite, kCompute, kStorageReadWrite);
            vkCmdPushConstants(cmd, compute_layout_.handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                               sizeof(constants), &constants);
            vkCmdDispatch(cmd, groups_x, groups_y, 1);
        }
    } else {
        vkCmdPushConstants(cmd, compute_layout_.handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0,
                           sizeof(constants), &constants);
        vkCmdDispatch(cmd, groups_x, groups_y, 1);
    }
    timestamps_.write(cmd, kCompute, kTsLighting);

    // Output: tone mapping or cut visualisation into the display image.
    vk::memory_barrier(cmd, kCompute, kStorageWrite, kCompute, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    vk::transition_image(cmd, {targets_.display.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
                               VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                               VK_ACCESS_2_MEMORY_READ_BIT, kCompute, kStorageWrite});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, *output);
    vkCmdDispatch(cmd, groups_x, groups_y, 1);
    timestamps_.write(cmd, kCompute, kTsOutput);

    // Results become readable by copies (read-backs, blits) and by the host (counters).
    vk::memory_barrier(cmd, kCompute, kStorageWrite,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
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
    LC_RETURN_IF_ERROR(validate(settings));
    // Build targets and pipelines before the clock starts: wall_ms is the frame.
    LC_RETURN_IF_ERROR(ensure_targets(settings.width, settings.height));
    if (auto p = gbuffer_pipeline(); !p) return make_error(p.error());
    if (auto p = lighting_pipeline(settings); !p) return make_error(p.error());
    if (auto p = output_pipeline(settings.mode); !p) return make_error(p.error());

    auto start = std::chrono::steady_clock::now();
    Status recorded = Ok{};
    LC_RETURN_IF_ERROR(context_.command_pool().run_one_time(
        context_.device(), [&](VkCommandBuffer cmd) { recorded = record(cmd, settings); }));
    LC_RETURN_IF_ERROR(recorded);
    double wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    RenderStats stats;
    stats.mode = render_mode_name(settings.mode);
    stats.criterion = mode_needs_tree(settings.mode) ? criterion_name(settings.criterion) : "none";
    stats.device = context_.physical().name();
    stats.width = settings.width;
    stats.height = settings.height;
    stats.lights = uint64_t(leaf_count_) + classic_count_;
    stats.tree_lights = has_tree_ ? leaf_count_ : 0;
    stats.classic_lights = classic_count_;
    stats.nodes = node_count_;
    stats.tree_depth = tree_depth_;
    stats.wall_ms = wall_ms;

    Result<PassTimings> timings = read_timings();
    if (!timings) return make_error(timings.error());
    stats.render_ms = timings->total_ms;
    stats.gbuffer_ms = timings->gbuffer_ms;
    stats.lighting_ms = timings->lighting_ms;
    stats.output_ms = timings->output_ms;

    Result<GpuFrameCounters> counters = read_counters();
    if (!counters) return make_error(counters.error());
    stats.max_cut = counters->max_cut;
    stats.geometry_pixels = counters->geometry_pixels;
    stats.nonfinite_pixels = counters->nonfinite_pixels;
    stats.max_cut_hits = counters->max_cut_hits;
    stats.loop_limit_stops = counters->loop_limit_stops;
    stats.shadows = traces_shadows();
    stats.shadow_rays = (uint64_t(counters->shadow_rays_high) << 32) | counters->shadow_rays;
    stats.shadow_triangles = shadow_bvh_.stats().triangles;
    stats.shadow_bvh_nodes = shadow_bvh_.stats().nodes;
    if (settings.mode == RenderMode::kReference) {
        const uint32_t chunk = reference_chunk();
        stats.reference_dispatches = (std::max(leaf_count_, 1u) + chunk - 1) / chunk;
    }
    if (mode_needs_tree(settings.mode) && settings.criterion == CutCriterion::kBound) {
        stats.error_ratio = settings.error_ratio;
        stats.max_cut_setting = settings.max_cut;
        stats.bound_search = bound_search_name(settings.bound_search);
    }

    Result<std::vector<uint32_t>> cuts = read_cuts();
    if (!cuts) return make_error(cuts.error());
    uint64_t cut_sum = 0;
    std::vector<uint32_t> geometry_cuts;  // for the percentile: pixels with a cut
    geometry_cuts.reserve(cuts->size() / 2);
    for (size_t i = 0; i < cuts->size(); i += 2) {
        cut_sum += (*cuts)[i];  // 0 on background
        if ((*cuts)[i] > 0) geometry_cuts.push_back((*cuts)[i]);
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
