#pragma once
// Reconstruction cuts' storage on the GPU (set kReconstructionSet of
// ReconstructionPass's layout): per sample of the lattice a header
// (GpuReconstructionSample) and room for `cap` cut records (GpuCutRecord).
// Sized per frame; it only grows, so a smaller frame reuses it.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/device.h"
#include "lightcuts/result.h"

namespace lc::client {

// Samples along one axis of `side` pixels with blocks of `block`: every
// block-th pixel and the last (shaders/reconstruction_bindings.glsl).
uint32_t reconstruction_lattice_side(uint32_t side, uint32_t block);

// Bytes the samples' headers and records take for one frame.
uint64_t reconstruction_bytes(uint32_t width, uint32_t height, uint32_t block, uint32_t cap);

class ReconstructionRecords {
public:
    static Result<ReconstructionRecords> create(const vk::Device& device);

    // Room for a width x height frame's samples with `cap` records each. The
    // caller has waited for the frames that read the old buffers.
    Status reserve(uint32_t width, uint32_t height, uint32_t block, uint32_t cap);

    VkDescriptorSetLayout set_layout() const { return set_layout_.handle(); }
    VkDescriptorSet descriptor_set() const { return set_; }

private:
    explicit ReconstructionRecords(const vk::Device& device) : device_(&device) {}

    const vk::Device* device_;
    vk::DescriptorSetLayout set_layout_;
    vk::DescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    vk::Buffer samples_;
    vk::Buffer records_;
};

}  // namespace lc::client
