#include "editor_client/render/gpu/frame_measurements.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace lc::client {
namespace {

// Timestamp slots: start, then the end of each pass.
enum Timestamp : uint32_t { kTsStart = 0, kTsGBuffer = 1, kTsLighting = 2, kTsOutput = 3, kTsCount = 4 };

}  // namespace

void add_counters(GpuFrameCounters& sum, const GpuFrameCounters& part) {
    sum.max_cut = std::max(sum.max_cut, part.max_cut);
    sum.nonfinite_pixels += part.nonfinite_pixels;
    sum.geometry_pixels += part.geometry_pixels;
    sum.max_cut_hits += part.max_cut_hits;
    sum.loop_limit_stops += part.loop_limit_stops;
    sum.reconstruction_fallbacks += part.reconstruction_fallbacks;
    const uint64_t rays = ((uint64_t(sum.shadow_rays_high) << 32) | sum.shadow_rays) +
                          ((uint64_t(part.shadow_rays_high) << 32) | part.shadow_rays);
    sum.shadow_rays = uint32_t(rays);
    sum.shadow_rays_high = uint32_t(rays >> 32);
}

void add_timings(PassTimings& sum, const PassTimings& part) {
    sum.gbuffer_ms += part.gbuffer_ms;
    sum.lighting_ms += part.lighting_ms;
    sum.output_ms += part.output_ms;
    sum.total_ms += part.total_ms;
}

Status FrameMeasurements::create(const vk::Context& context) {
    Result<vk::Buffer> counters =
        vk::Buffer::create(context.device(), sizeof(GpuFrameCounters),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           vk::MemoryUsage::kHostReadback);
    if (!counters) return make_error(counters.error());
    counters_ = std::move(counters).value();
    Result<vk::TimestampQueryPool> timestamps = vk::TimestampQueryPool::create(context.device(), kTsCount);
    if (!timestamps) return make_error(timestamps.error());
    timestamps_ = std::move(timestamps).value();
    return Ok{};
}

void FrameMeasurements::begin(VkCommandBuffer cmd) const {
    timestamps_.reset(cmd);
    timestamps_.write(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, kTsStart);
    vkCmdFillBuffer(cmd, counters_.handle(), 0, VK_WHOLE_SIZE, 0);
}

void FrameMeasurements::end_pass(VkCommandBuffer cmd, VkPipelineStageFlags2 stage, uint32_t pass) const {
    timestamps_.write(cmd, stage, kTsStart + pass);
}

Result<PassTimings> FrameMeasurements::read_timings() const {
    Result<std::vector<double>> ms = timestamps_.read_ms();
    if (!ms) return make_error(ms.error());
    PassTimings t;
    t.gbuffer_ms = (*ms)[kTsGBuffer] - (*ms)[kTsStart];
    t.lighting_ms = (*ms)[kTsLighting] - (*ms)[kTsGBuffer];
    t.output_ms = (*ms)[kTsOutput] - (*ms)[kTsLighting];
    t.total_ms = (*ms)[kTsOutput] - (*ms)[kTsStart];
    return t;
}

GpuFrameCounters FrameMeasurements::read_counters() const {
    GpuFrameCounters counters;
    std::memcpy(&counters, counters_.mapped(), sizeof(counters));
    return counters;
}

}  // namespace lc::client
