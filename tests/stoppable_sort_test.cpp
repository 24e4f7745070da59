// The tree builder's stoppable sort (issue 27): the order std::sort gives, and
// a stop seen within one merge stride even in the widest merge.
#include "lightmass_server/builders/stoppable_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace lc::bake {
namespace {

struct Keyed {
    uint32_t key;
    uint32_t tag;  // equal keys carry equal tags: equal elements are alike in every byte
    bool operator<(const Keyed& o) const { return key < o.key; }
    bool operator==(const Keyed& o) const { return key == o.key && tag == o.tag; }
};

std::vector<Keyed> random_items(size_t count, uint32_t key_range, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<uint32_t> key(0, key_range);
    std::vector<Keyed> items(count);
    for (Keyed& item : items) {
        item.key = key(rng);
        item.tag = item.key * 2654435761u;
    }
    return items;
}

TEST(StoppableSort, GivesStdSortsOrderAtSizesAroundItsRunsAndMerges) {
    for (const size_t count : {0u, 1u, 1000u, 65536u, 65537u, 200000u, 262144u, 300001u}) {
        std::vector<Keyed> items = random_items(count, uint32_t(count / 3 + 1), 11 + count);
        std::vector<Keyed> expected = items;
        std::sort(expected.begin(), expected.end());
        BakeStop live;
        StopPoll poll(&live);
        EXPECT_TRUE(stoppable_sort(std::span<Keyed>(items), std::less<Keyed>(), poll)) << count;
        EXPECT_EQ(items, expected) << count;
    }
}

// Cancelled inside the last (widest) merge, the sort compares at most one
// merge stride more: the merge asks the stop, not only the runs between merges.
TEST(StoppableSort, AStopInTheWidestMergeEndsItWithinAStride) {
    // 3 x 2^18: the widest merge has the shorter right side, merged back to front.
    const std::vector<Keyed> input = random_items(size_t(3) << 18, 1u << 30, 5);
    uint64_t total = 0;
    std::vector<Keyed> items = input;
    StopPoll unstopped(nullptr);
    ASSERT_TRUE(stoppable_sort(std::span<Keyed>(items), [&](const Keyed& a, const Keyed& b) {
        ++total;
        return a < b;
    }, unstopped));

    BakeStop stop;
    StopPoll poll(&stop);
    items = input;
    const uint64_t cancel_at = total - 300000;  // the widest merge compares about 786,000 times
    uint64_t compared = 0;
    const bool sorted = stoppable_sort(std::span<Keyed>(items), [&](const Keyed& a, const Keyed& b) {
        if (++compared == cancel_at) stop.cancel();
        return a < b;
    }, poll);
    EXPECT_FALSE(sorted);
    EXPECT_LE(compared - cancel_at, 4096u);
}

}  // namespace
}  // namespace lc::bake
