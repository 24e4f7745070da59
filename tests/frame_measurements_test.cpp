// FrameMeasurements' sums: a long reference's submissions are timed and
// counted one by one, and Renderer::render reports their sum.
#include <gtest/gtest.h>

#include <cstdint>

#include "editor_client/render/gpu/frame_measurements.h"

namespace lc::client {
namespace {

GpuFrameCounters counters(uint32_t max_cut, uint32_t pixels, uint64_t shadow_rays) {
    GpuFrameCounters c;
    c.max_cut = max_cut;
    c.nonfinite_pixels = 1;
    c.geometry_pixels = pixels;
    c.max_cut_hits = 2;
    c.loop_limit_stops = 3;
    c.shadow_rays = uint32_t(shadow_rays);
    c.shadow_rays_high = uint32_t(shadow_rays >> 32);
    return c;
}

uint64_t shadow_rays(const GpuFrameCounters& c) {
    return (uint64_t(c.shadow_rays_high) << 32) | c.shadow_rays;
}

TEST(FrameMeasurements, CountersAddAndTheLargestCutStays) {
    GpuFrameCounters sum;
    add_counters(sum, counters(40, 100, 7));
    add_counters(sum, counters(25, 50, 5));
    EXPECT_EQ(sum.max_cut, 40u);
    EXPECT_EQ(sum.geometry_pixels, 150u);
    EXPECT_EQ(sum.nonfinite_pixels, 2u);
    EXPECT_EQ(sum.max_cut_hits, 4u);
    EXPECT_EQ(sum.loop_limit_stops, 6u);
    EXPECT_EQ(shadow_rays(sum), 12u);
}

TEST(FrameMeasurements, ShadowRaysCarryIntoTheHighWord) {
    GpuFrameCounters sum = counters(1, 1, 0xFFFFFFF0u);
    add_counters(sum, counters(1, 1, 0x20u));
    EXPECT_EQ(sum.shadow_rays_high, 1u);
    EXPECT_EQ(shadow_rays(sum), 0x100000010u);
    add_counters(sum, counters(1, 1, uint64_t(3) << 32));
    EXPECT_EQ(shadow_rays(sum), 0x400000010u);
}

TEST(FrameMeasurements, PassTimingsAddPassByPass) {
    PassTimings sum;
    add_timings(sum, PassTimings{1.0, 10.0, 0.5, 11.5});
    add_timings(sum, PassTimings{0.0, 20.0, 0.25, 20.25});
    EXPECT_DOUBLE_EQ(sum.gbuffer_ms, 1.0);
    EXPECT_DOUBLE_EQ(sum.lighting_ms, 30.0);
    EXPECT_DOUBLE_EQ(sum.output_ms, 0.75);
    EXPECT_DOUBLE_EQ(sum.total_ms, 31.75);
}

}  // namespace
}  // namespace lc::client
