#pragma once
// GPU timestamps around each pass; results in milliseconds.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "editor_client/vk/device.h"
#include "editor_client/vk/device_handle.h"
#include "lightcuts/result.h"

namespace lc::vk {

class TimestampQueryPool {
public:
    static Result<TimestampQueryPool> create(const Device& device, uint32_t count);

    // False when the queue cannot write timestamps (timings then read as 0).
    bool supported() const { return supported_; }
    uint32_t count() const { return count_; }

    void reset(VkCommandBuffer cmd) const;
    void write(VkCommandBuffer cmd, VkPipelineStageFlags2 stage, uint32_t index) const;
    // Waits for every query, returns the raw ticks converted to milliseconds
    // since query 0 (all zeros when unsupported).
    Result<std::vector<double>> read_ms() const;

private:
    DeviceHandle<VkQueryPool> pool_;
    uint32_t count_ = 0;
    double period_ns_ = 1.0;
    uint64_t valid_mask_ = ~0ull;
    bool supported_ = false;
};

}  // namespace lc::vk
