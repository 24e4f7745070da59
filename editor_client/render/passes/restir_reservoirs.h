#pragma once
// The ReSTIR mode's reservoirs on the GPU (set kRestirSet of RestirPass's
// layout, lightcuts/device/restir.h): one GpuReservoir per pixel for the
// previous frame's final reservoirs, this frame's after temporal reuse, and
// this frame's final ones. The previous and final buffers swap every frame
// (two descriptor sets, like TemporalHistory's images).
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/descriptor_set.h"
#include "editor_client/vk/device.h"
#include "lightcuts/result.h"

namespace lc::client {

class RestirReservoirs {
public:
    static Result<RestirReservoirs> create(const vk::Device& device);

    VkDescriptorSetLayout set_layout() const { return set_layout_.handle(); }
    // Sizes the buffers for a width x height frame (remade when it differs:
    // the caller's history is dropped with them, as TemporalHistory's is).
    Status prepare(uint32_t width, uint32_t height);
    // The set binding this frame's reservoirs (prepare first).
    VkDescriptorSet descriptor_set() const { return sets_[parity_]; }
    // After a frame was recorded: its final reservoirs are the next one's previous.
    void advance() { parity_ = 1 - parity_; }

private:
    explicit RestirReservoirs(const vk::Device& device) : device_(&device) {}
    void bind_sets();

    const vk::Device* device_;
    vk::DescriptorSetLayout set_layout_;
    vk::DescriptorPool pool_;
    std::array<VkDescriptorSet, 2> sets_{};
    std::array<vk::Buffer, 3> buffers_;  // [0], [1]: previous and final by turns; [2]: after temporal reuse
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    uint32_t parity_ = 0;
};

}  // namespace lc::client
