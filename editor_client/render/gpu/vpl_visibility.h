#pragma once
// Reference mode's exact clamp keeps each VPL's visibility for its Newton
// passes, one bit per pixel and leaf (GpuVisibilityBits), when it fits a
// budget; a larger frame traces the rays again in every pass.
#include <vulkan/vulkan.h>

#include <cstdint>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "lightcuts/result.h"

namespace lc::client {

class VplVisibility {
public:
    // A buffer of at least `bytes`: true when it was made anew.
    Result<bool> ensure(const vk::Context& context, uint64_t bytes);
    // The visibility of a frame of `pixels` over `leaf_count` leaves, kept
    // where `clamps` (the frame runs the exact clamp with shadow rays) and
    // within `budget_bytes`: true when the buffer was made anew.
    Result<bool> prepare(const vk::Context& context, bool clamps, uint32_t leaf_count, uint64_t pixels,
                         uint64_t budget_bytes);
    // GpuVisibilityBits per pixel of the frame being recorded; 0: none kept.
    uint32_t stride() const { return stride_; }
    VkBuffer buffer() const { return buffer_.handle(); }

private:
    vk::Buffer buffer_;
    uint32_t stride_ = 0;
};

}  // namespace lc::client
