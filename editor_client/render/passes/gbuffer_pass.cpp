#include "editor_client/render/passes/gbuffer_pass.h"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "editor_client/render/passes/compute_pass.h"
#include "editor_client/vk/barriers.h"
#include "gbuffer_frag.spv.h"
#include "gbuffer_vert.spv.h"

namespace lc::client {

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

glm::mat4 eye_ray_view_projection(const RenderSettings& settings, uint32_t width,
                                   uint32_t height, const glm::vec3& bounds_min,
                                   const glm::vec3& bounds_max) {
    // The image the camera frames: the frame itself, or the one whose pixel
    // corners the frame's pixels are.
    const float image_width = float(width - (settings.corner_grid ? 1u : 0u));
    const float image_height = float(height - (settings.corner_grid ? 1u : 0u));
    glm::mat4 clip(1.0f);
    // Corner grid: the image's pixel pitch kept, pixel centres on its corners.
    clip[0][0] = image_width / float(width);
    clip[1][1] = image_height / float(height);
    // The eye ray of a pixel passes `pixel_offset` from its centre: the scene
    // moves the other way (NDC spans 2 over the frame; y grows with rows).
    clip[3][0] = -2.0f * settings.pixel_offset.x / float(width);
    clip[3][1] = -2.0f * settings.pixel_offset.y / float(height);
    return clip * view_projection(settings.camera, image_width / image_height, bounds_min,
                                  bounds_max);
}

GBufferPass::GBufferPass(const GpuScene& gpu_scene, const Scene& scene, vk::PipelineLayout layout)
    : gpu_scene_(gpu_scene), scene_(scene), layout_(std::move(layout)) {}

Result<std::unique_ptr<GBufferPass>> GBufferPass::create(VkDevice device, const GpuScene& gpu_scene,
                                                         const Scene& scene) {
    VkDescriptorSetLayout material_layout = gpu_scene.material_layout().handle();
    VkPushConstantRange draw_constants{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                       sizeof(GpuDrawConstants)};
    Result<vk::PipelineLayout> layout = vk::PipelineLayout::create(
        device, std::span(&material_layout, 1), std::span(&draw_constants, 1));
    if (!layout) return make_error(layout.error());
    return std::unique_ptr<GBufferPass>(
        new GBufferPass(gpu_scene, scene, std::move(layout).value()));
}

Status GBufferPass::prepare(PipelineCache& pipelines, const Frame& frame) {
    vk::Specialization fragment;
    fragment.set_bool(kSpecTextures, frame.effects->textures);
    vk::GraphicsPipelineDesc desc;
    desc.layout = layout_.handle();
    desc.vertex_spirv = spirv_words(gbuffer_vert_spv);
    desc.fragment_spirv = spirv_words(gbuffer_frag_spv);
    desc.fragment_specialization = &fragment;
    desc.vertex_bindings = {{0, sizeof(GpuVertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    desc.vertex_attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, position)},
                              {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(GpuVertex, normal)},
                              {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(GpuVertex, uv)},
                              {3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(GpuVertex, tangent)},
                              {4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(GpuVertex, color)}};
    desc.color_formats = {kGBufferFormat, kGBufferFormat, kGBufferFormat, kGBufferFormat};
    desc.depth_format = kDepthFormat;
    desc.cull_mode = VK_CULL_MODE_NONE;  // surfaces are lit on the side the camera sees
    Result<VkPipeline> pipeline = pipelines.graphics(desc);
    if (!pipeline) return make_error("G-buffer pipeline: " + pipeline.error());
    pipeline_ = *pipeline;
    return Ok{};
}

void GBufferPass::record(VkCommandBuffer cmd, const Frame& frame) const {
    const RenderTargets& targets = *frame.targets;
    const std::array<const vk::Image*, 4> colors{&targets.position, &targets.normal,
                                                 &targets.albedo, &targets.emissive};
    for (const vk::Image* image : colors) {
        vk::transition_image(cmd, {image->handle(), VK_IMAGE_LAYOUT_UNDEFINED,
                                   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kComputeStage,
                                   VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                                   VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                   VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT});
    }
    vk::transition_image(
        cmd, {targets.depth.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
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
    depth.imageView = targets.depth.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {targets.width, targets.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = uint32_t(color_attachments.size());
    rendering.pColorAttachments = color_attachments.data();
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);
    draw(cmd, frame);
    vkCmdEndRendering(cmd);

    for (const vk::Image* image : colors) {
        vk::transition_image(
            cmd, {image->handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, kComputeStage,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT});
    }
}

void GBufferPass::draw(VkCommandBuffer cmd, const Frame& frame) const {
    const RenderTargets& targets = *frame.targets;
    VkViewport viewport{0.0f, 0.0f, float(targets.width), float(targets.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {targets.width, targets.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    if (gpu_scene_.draws().empty()) return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    VkBuffer vertex_buffer = gpu_scene_.vertex_buffer();
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, gpu_scene_.index_buffer(), 0, VK_INDEX_TYPE_UINT32);
    const RenderCamera& camera = frame.settings->camera;
    GpuDrawConstants constants;
    constants.view_proj = eye_ray_view_projection(*frame.settings, targets.width, targets.height,
                                                  scene_.bounds_min, scene_.bounds_max);
    constants.eye_roughness = glm::vec4(camera.eye, 0.0f);
    for (const GpuDraw& d : gpu_scene_.draws()) {
        const GpuMaterial& material = gpu_scene_.materials()[d.material];
        constants.base_color_factor = material.base_color_factor;
        constants.emissive_metallic = glm::vec4(material.emissive_factor, material.metallic);
        constants.eye_roughness.w = material.roughness;
        constants.flags = material.flags | (d.vertex_colors ? kDrawVertexColors : 0u);
        constants.alpha_cutoff = material.alpha_cutoff;
        constants.normal_scale = material.normal_scale;
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.handle(), 0, 1,
                                &material.set, 0, nullptr);
        vkCmdPushConstants(cmd, layout_.handle(),
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(constants), &constants);
        vkCmdDrawIndexed(cmd, d.index_count, 1, d.first_index, d.vertex_offset, 0);
    }
}

}  // namespace lc::client
