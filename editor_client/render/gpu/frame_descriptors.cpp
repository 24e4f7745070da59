#include "editor_client/render/gpu/frame_descriptors.h"

#include <array>

#include "editor_client/render/gpu/frame_set_layout.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/gpu_structs.h"

namespace lc::client {

Status FrameDescriptors::create(VkDevice device) {
    Result<vk::DescriptorSetLayout> layout = create_frame_set_layout(device);
    if (!layout) return make_error(layout.error());
    layout_ = std::move(layout).value();
    std::array<VkDescriptorPoolSize, 2> sizes{
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kBindLeafLights},
        VkDescriptorPoolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kFrameBindingCount - kBindLeafLights}};
    Result<vk::DescriptorPool> pool = vk::DescriptorPool::create(device, 1, sizes);
    if (!pool) return make_error(pool.error());
    pool_ = std::move(pool).value();
    Result<VkDescriptorSet> set = pool_.allocate(layout_);
    if (!set) return make_error(set.error());
    set_ = *set;

    VkDescriptorSetLayout frame_layout = layout_.handle();
    VkPushConstantRange frame_constants{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GpuFrameConstants)};
    Result<vk::PipelineLayout> compute_layout =
        vk::PipelineLayout::create(device, std::span(&frame_layout, 1), std::span(&frame_constants, 1));
    if (!compute_layout) return make_error(compute_layout.error());
    compute_layout_ = std::move(compute_layout).value();
    dirty_ = true;
    return Ok{};
}

void FrameDescriptors::update(VkDevice device, const RenderTargets& targets, const GpuLights& lights,
                              const GpuOccluders& occluders, const BackgroundBuffers& background,
                              const FrameBuffers& buffers) {
    if (!dirty_) return;
    vk::DescriptorWriter(set_)
        .storage_image(kBindPosition, targets.position.view())
        .storage_image(kBindNormal, targets.normal.view())
        .storage_image(kBindAlbedo, targets.albedo.view())
        .storage_image(kBindEmissive, targets.emissive.view())
        .storage_image(kBindHdr, targets.hdr.view())
        .storage_image(kBindCut, targets.cut.view())
        .storage_image(kBindDisplay, targets.display.view())
        .storage_buffer(kBindLeafLights, lights.leaves())
        .storage_buffer(kBindTreeNodes, lights.nodes())
        .storage_buffer(kBindClassicLights, lights.classic())
        .storage_buffer(kBindCounters, buffers.counters)
        .storage_buffer(kBindBvhNodes, occluders.nodes())
        .storage_buffer(kBindShadowTriangles, occluders.triangles())
        .storage_buffer(kBindMaskedTriangles, occluders.masked_triangles())
        .storage_buffer(kBindAlphaMasks, occluders.alpha_masks())
        .storage_buffer(kBindMaskTexels, occluders.mask_texels())
        .storage_buffer(kBindWalkStates, targets.walk_states.handle())
        .storage_buffer(kBindVplVisibility, buffers.vpl_visibility)
        .storage_buffer(kBindBackground, background.frame())
        .storage_buffer(kBindEnvironmentTexels, background.texels())
        .update(device);
    dirty_ = false;
}

}  // namespace lc::client
