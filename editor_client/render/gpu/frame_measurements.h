#pragma once
// What the GPU measures of a frame: a timestamp at its start and at the end of
// each of its three passes, and the counters its shaders add to
// (GpuFrameCounters: cut sizes, pixels, shadow rays, loop-limit stops).
#include <vulkan/vulkan.h>

#include <cstdint>

#include "editor_client/vk/buffer.h"
#include "editor_client/vk/context.h"
#include "editor_client/vk/timestamp_query_pool.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/result.h"

namespace lc::client {

// GPU time of each pass of the last frame, in milliseconds.
struct PassTimings {
    double gbuffer_ms = 0.0;
    double lighting_ms = 0.0;
    double output_ms = 0.0;
    double total_ms = 0.0;
};

// One submission's timings and counters added to the frame's.
void add_timings(PassTimings& sum, const PassTimings& part);
void add_counters(GpuFrameCounters& sum, const GpuFrameCounters& part);

class FrameMeasurements {
public:
    Status create(const vk::Context& context);

    // Resets the timestamps, writes the start's and zeroes the counters.
    void begin(VkCommandBuffer cmd) const;
    // The end of a frame's pass: 1 the G-buffer, 2 the lighting, 3 the output.
    void end_pass(VkCommandBuffer cmd, VkPipelineStageFlags2 stage, uint32_t pass) const;
    Result<PassTimings> read_timings() const;
    GpuFrameCounters read_counters() const;
    VkBuffer counters() const { return counters_.handle(); }

private:
    vk::Buffer counters_;  // GpuFrameCounters, host-readable
    vk::TimestampQueryPool timestamps_;
};

}  // namespace lc::client
