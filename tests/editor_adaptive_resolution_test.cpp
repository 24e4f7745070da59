// Reduced resolution while moving, full resolution once the camera settles.
#include <gtest/gtest.h>

#include <cmath>

#include "editor_client/editor/adaptive_resolution.h"

namespace lc::client {
namespace {

TEST(EditorAdaptiveResolution, StillViewRendersAtFullSize) {
    AdaptiveResolution res;
    EXPECT_EQ(res.next_divisor(false, 0.0), 1u);
    res.report_frame(1, 800.0);
    EXPECT_EQ(res.next_divisor(false, 1000.0), 1u);
}

TEST(EditorAdaptiveResolution, MovingPicksTheSmallestDivisorMeetingTheTarget) {
    AdaptiveResolution res({.target_frame_ms = 100.0, .settle_ms = 200.0, .max_divisor = 4});
    // Before any measurement there is nothing to scale by.
    EXPECT_EQ(res.next_divisor(true, 0.0), 1u);
    res.report_frame(1, 350.0);  // 350 / 4 = 87.5 <= 100 -> divisor 2
    EXPECT_EQ(res.next_divisor(true, 10.0), 2u);
    AdaptiveResolution slow({.target_frame_ms = 100.0, .settle_ms = 200.0, .max_divisor = 4});
    slow.report_frame(1, 850.0);  // /4 = 212, /9 = 94 -> divisor 3
    EXPECT_EQ(slow.next_divisor(true, 0.0), 3u);
    AdaptiveResolution slower({.target_frame_ms = 100.0, .settle_ms = 200.0, .max_divisor = 4});
    slower.report_frame(2, 1000.0);  // full 4000 ms: even /16 misses; capped at 4
    EXPECT_EQ(slower.next_divisor(true, 0.0), 4u);
    EXPECT_DOUBLE_EQ(slower.full_frame_ms(), 4000.0);
}

TEST(EditorAdaptiveResolution, RefinesAfterTheViewSettles) {
    AdaptiveResolution res({.target_frame_ms = 50.0, .settle_ms = 200.0, .max_divisor = 4});
    res.report_frame(1, 400.0);
    EXPECT_GT(res.next_divisor(true, 1000.0), 1u);
    EXPECT_GT(res.next_divisor(false, 1100.0), 1u);  // still within the settle time
    EXPECT_EQ(res.next_divisor(false, 1200.0), 1u);  // settled: full resolution
    res.report_frame(1, std::nan(""));               // ignored
    EXPECT_GT(res.full_frame_ms(), 0.0);
}

TEST(EditorAdaptiveResolution, ReducedSizeRoundsUpAndNeverReachesZero) {
    EXPECT_EQ(reduced_size(640, 1), 640u);
    EXPECT_EQ(reduced_size(640, 3), 214u);
    EXPECT_EQ(reduced_size(1, 4), 1u);
    EXPECT_EQ(reduced_size(0, 1), 0u);
}

}  // namespace
}  // namespace lc::client
