#pragma once
// The images one frame renders into, for one size: the G-buffer (float
// attachments + depth), linear HDR radiance, the cut per pixel, the 8-bit
// display image, and the walk search's state per pixel between its passes.
#include <glm/vec3.hpp>

#include <cstdint>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/device.h"
#include "editor_client/vk/image.h"
#include "lightcuts/result.h"

namespace lc::client {

// Formats (mirrored by the image qualifiers in shaders/frame_bindings.glsl).
inline constexpr VkFormat kGBufferFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kHdrFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
inline constexpr VkFormat kCutFormat = VK_FORMAT_R32G32_UINT;
inline constexpr VkFormat kDisplayFormat = VK_FORMAT_R8G8B8A8_UNORM;

struct RenderTargets {
    static Result<RenderTargets> create(const vk::Device& device, uint32_t width, uint32_t height);

    uint32_t width = 0;
    uint32_t height = 0;
    // Full float keeps the positions and normals the lighting pass reads
    // identical to what tests read back and feed the CPU evaluator.
    vk::Image position;  // xyz world position, w = 1 on geometry, 0 on background
    vk::Image normal;    // xyz unit normal facing the camera, w roughness
    vk::Image albedo;    // rgb linear base colour, a metallic
    vk::Image emissive;  // rgb linear emitted radiance
    vk::Image depth;
    vk::Image hdr;      // linear radiance
    vk::Image cut;      // x cut size, y cut hash
    vk::Image display;  // tone-mapped (or visualised), sRGB-encoded
    vk::Buffer walk_states;  // GpuWalkState per pixel (gpu_layout.h), GPU only
    glm::vec3 gbuffer_eye{0.0f};  // the camera the G-buffer was last drawn from (its read-back's view)
};

}  // namespace lc::client
