#include "editor_client/render/passes/primary_rays_pass.h"

#include <glm/matrix.hpp>

#include <array>
#include <string>

#include "editor_client/render/passes/compute_pass.h"
#include "editor_client/render/passes/gbuffer_pass.h"
#include "editor_client/render/gpu/primary_geometry.h"
#include "editor_client/vk/barriers.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/status_macros.h"
#include "primary_rays_comp.spv.h"

namespace lc::client {
namespace {

template <typename T>
std::span<const std::byte> bytes_of(const std::vector<T>& v) {
    return std::as_bytes(std::span(v));
}

}  // namespace

PrimaryRaysPass::PrimaryRaysPass(const vk::Context& context, const GpuScene& gpu_scene, const Scene& scene)
    : context_(context), gpu_scene_(gpu_scene), scene_(scene), unsupported_(primary_rays_unsupported(gpu_scene)) {}

Result<std::unique_ptr<PrimaryRaysPass>> PrimaryRaysPass::create(const vk::Context& context,
                                                                 VkDescriptorSetLayout frame_layout,
                                                                 const GpuScene& gpu_scene,
                                                                 const Scene& scene) {
    std::unique_ptr<PrimaryRaysPass> pass(new PrimaryRaysPass(context, gpu_scene, scene));
    VkDevice device = context.device().handle();
    std::array<VkDescriptorType, kPrimaryBindingCount> types{};
    types.fill(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    Result<vk::DescriptorSetLayout> set_layout =
        vk::DescriptorSetLayout::create(device, types, VK_SHADER_STAGE_COMPUTE_BIT);
    if (!set_layout) return make_error(set_layout.error());
    pass->set_layout_ = std::move(set_layout).value();
    const std::array<VkDescriptorPoolSize, 1> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kPrimaryBindingCount}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device, 1, sizes);
    if (!pool) return make_error(pool.error());
    pass->pool_ = std::move(pool).value();
    Result<VkDescriptorSet> set = pass->pool_.allocate(pass->set_layout_);
    if (!set) return make_error(set.error());
    pass->set_ = *set;
    static_assert(kPrimarySet == 1u);
    const std::array<VkDescriptorSetLayout, 2> sets{frame_layout, pass->set_layout_.handle()};
    VkPushConstantRange constants{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GpuFrameConstants)};
    Result<vk::PipelineLayout> layout = vk::PipelineLayout::create(device, sets, std::span(&constants, 1));
    if (!layout) return make_error(layout.error());
    pass->layout_ = std::move(layout).value();
    return pass;
}

Status PrimaryRaysPass::upload(vk::Buffer& out, std::span<const std::byte> bytes) {
    Result<vk::Buffer> buffer = vk::Buffer::create_with_data(context_.device(), context_.command_pool(),
                                                             bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!buffer) return make_error("primary rays: " + buffer.error());
    out = std::move(buffer).value();
    return Ok{};
}

// The BVH over every triangle, its triangles' vertices and draws in the BVH's
// leaf order, and the draws' materials.
Status PrimaryRaysPass::build_geometry() {
    const PrimaryGeometry geometry = primary_geometry(scene_, gpu_scene_);
    const ShadowBvh bvh = ShadowBvh::build(geometry.triangle_vertices);
    std::vector<GpuPrimaryTriangle> sources;
    sources.reserve(bvh.leaf_sources().size());
    for (uint32_t source : bvh.leaf_sources()) sources.push_back(geometry.triangles[source]);
    LC_RETURN_IF_ERROR(upload(nodes_, bytes_of(bvh.gpu_nodes())));
    LC_RETURN_IF_ERROR(upload(triangles_, bytes_of(bvh.gpu_triangles())));
    LC_RETURN_IF_ERROR(upload(sources_, bytes_of(sources)));
    LC_RETURN_IF_ERROR(upload(materials_, bytes_of(geometry.draw_materials)));
    Result<vk::Buffer> params = vk::Buffer::create(
        context_.device(), sizeof(GpuPrimaryParams),
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUsage::kDeviceLocal);
    if (!params) return make_error("primary rays: " + params.error());
    params_buffer_ = std::move(params).value();
    vk::DescriptorWriter(set_)
        .storage_buffer(kBindPrimaryNodes, nodes_.handle())
        .storage_buffer(kBindPrimaryTriangles, triangles_.handle())
        .storage_buffer(kBindPrimarySources, sources_.handle())
        .storage_buffer(kBindSceneVertices, gpu_scene_.vertex_buffer())
        .storage_buffer(kBindSurfaceMaterials, materials_.handle())
        .storage_buffer(kBindPrimaryParams, params_buffer_.handle())
        .update(context_.device().handle());
    node_count_ = uint32_t(bvh.gpu_nodes().size());
    built_ = true;
    return Ok{};
}

Status PrimaryRaysPass::prepare(PipelineCache& pipelines, const Frame& frame) {
    if (!unsupported_.empty()) return make_error("primary rays: " + unsupported_ + "; use --primary raster");
    if (!built_) LC_RETURN_IF_ERROR(build_geometry());
    // A walk visits each node once at most: a BVH the loop limit cannot cover is refused.
    const vk::DeviceQuirks& quirks = context_.physical().quirks;
    if (quirks.has_loop_limit() && node_count_ >= quirks.loop_iteration_limit)
        return make_error("primary rays: the BVH's " + std::to_string(node_count_) +
                          " nodes exceed this device's shader loop limit; use --primary raster");
    const RenderSettings& settings = *frame.settings;
    // Inverted in double: the near plane may sit 1e-5 of the far one away,
    // and a float inverse then moves the rays by a fraction of a pixel.
    const glm::dmat4 view_proj(eye_ray_view_projection(settings, frame.targets->width, frame.targets->height,
                                                       scene_.bounds_min, scene_.bounds_max));
    params_.inverse_view_proj = glm::mat4(glm::inverse(view_proj));
    params_.eye = settings.camera.eye;
    params_.node_count = node_count_;
    vk::Specialization spec;
    spec.set_uint(kSpecWorkgroupX, frame.workgroup_size).set_uint(kSpecWorkgroupY, frame.workgroup_size);
    Result<VkPipeline> pipeline = pipelines.compute(layout_.handle(), spirv_words(primary_rays_comp_spv), spec);
    if (!pipeline) return make_error("primary rays pipeline: " + pipeline.error());
    pipeline_ = *pipeline;
    return Ok{};
}

void PrimaryRaysPass::record(VkCommandBuffer cmd, const Frame& frame) const {
    const RenderTargets& targets = *frame.targets;
    for (const vk::Image* image : {&targets.position, &targets.normal, &targets.albedo, &targets.emissive}) {
        vk::transition_image(cmd, {image->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                                   kComputeStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, kComputeStage,
                                   kStorageWrite});
    }
    vkCmdUpdateBuffer(cmd, params_buffer_.handle(), 0, sizeof(params_), &params_);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       kComputeStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    const std::array<VkDescriptorSet, 2> sets{frame.frame_set, set_};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.handle(), 0,
                            uint32_t(sets.size()), sets.data(), 0, nullptr);
    vkCmdPushConstants(cmd, layout_.handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(frame.constants),
                       &frame.constants);
    const uint32_t size = frame.workgroup_size;
    vkCmdDispatch(cmd, (targets.width + size - 1) / size, (targets.height + size - 1) / size, 1);
    // The lighting passes read what this wrote.
    vk::memory_barrier(cmd, kComputeStage, kStorageWrite, kComputeStage, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

VkPipelineStageFlags2 PrimaryRaysPass::last_stage() const { return kComputeStage; }

}  // namespace lc::client
