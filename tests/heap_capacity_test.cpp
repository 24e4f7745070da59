// The heap search's capacities (editor_client/render/passes/bound_heap_pass.h):
// where a driver refuses max-cut entries of private memory, the pass tries
// fewer, each at least three quarters of the last, down to kMinHeapCapacity.
#include <gtest/gtest.h>

#include "editor_client/render/passes/bound_heap_pass.h"

namespace lc::client {
namespace {

TEST(HeapCapacity, TriesMaxCutFirstThenShrinksByQuartersToTheFloor) {
    for (uint32_t max_cut : {17u, 100u, 1000u, 4096u}) {
        const std::vector<uint32_t> tries = heap_capacities(max_cut);
        ASSERT_FALSE(tries.empty());
        EXPECT_EQ(tries.front(), max_cut);
        EXPECT_EQ(tries.back(), kMinHeapCapacity);
        for (size_t i = 1; i < tries.size(); ++i) {
            EXPECT_LT(tries[i], tries[i - 1]);
            EXPECT_GE(4 * tries[i] + 4, 3 * tries[i - 1]) << "a step skips too much";
        }
    }
    // NVIDIA's H200 refused 1,000 entries and took 256: a try falls between.
    const std::vector<uint32_t> tries = heap_capacities(1000);
    EXPECT_NE(std::find_if(tries.begin(), tries.end(), [](uint32_t c) { return c > 256 && c < 1000; }),
              tries.end());
}

TEST(HeapCapacity, SmallCutsKeepRoomForOneRefinement) {
    EXPECT_EQ(heap_capacities(1), std::vector<uint32_t>{2});
    EXPECT_EQ(heap_capacities(16), std::vector<uint32_t>{16});
}

}  // namespace
}  // namespace lc::client
