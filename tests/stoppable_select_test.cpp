// The k-d tree's stoppable selection (issue 27): under a strict total order it
// splits a range into the same two sets as std::nth_element, with the same
// element at nth, on sorted, reversed and random input around its direct
// size; a stop ends it early, and a null stop never does.
#include "lightmass_server/builders/stoppable_select.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace lc::bake {
namespace {

// Indices ordered by a coarse key (many ties), then by index: a strict total order.
struct ByKey {
    const std::vector<uint32_t>* keys;
    bool operator()(uint32_t a, uint32_t b) const {
        return (*keys)[a] < (*keys)[b] || ((*keys)[a] == (*keys)[b] && a < b);
    }
};

std::vector<uint32_t> iota(size_t count) {
    std::vector<uint32_t> v(count);
    for (size_t i = 0; i < count; ++i) v[i] = uint32_t(i);
    return v;
}

TEST(StoppableSelect, SplitsIntoStdNthElementsSets) {
    for (const size_t count : {size_t(1000), kSelectDirect + 1, size_t(200000), size_t(1) << 20}) {
        for (int shape = 0; shape < 3; ++shape) {
            std::mt19937 rng(uint32_t(count) + uint32_t(shape));
            std::vector<uint32_t> keys(count);
            for (size_t i = 0; i < count; ++i)
                keys[i] = shape == 0 ? uint32_t(rng() % 1000) : shape == 1 ? uint32_t(i / 7) : uint32_t(count - i);
            const ByKey less{&keys};
            std::vector<uint32_t> ours = iota(count), theirs = iota(count);
            std::shuffle(ours.begin(), ours.end(), rng);
            theirs = ours;
            for (const size_t nth : {size_t(0), count / 3, count / 2, count - 1}) {
                StopPoll poll(nullptr);
                ASSERT_TRUE(stoppable_nth_element(ours.data(), 0, nth, count, less, poll));
                std::nth_element(theirs.begin(), theirs.begin() + ptrdiff_t(nth), theirs.end(), less);
                ASSERT_EQ(ours[nth], theirs[nth]) << count << " " << shape << " " << nth;
                std::vector<uint32_t> a(ours.begin(), ours.begin() + ptrdiff_t(nth));
                std::vector<uint32_t> b(theirs.begin(), theirs.begin() + ptrdiff_t(nth));
                std::sort(a.begin(), a.end());
                std::sort(b.begin(), b.end());
                ASSERT_EQ(a, b) << count << " " << shape << " " << nth;
            }
        }
    }
}

TEST(StoppableSelect, AStopEndsItBeforeItFinishes) {
    const size_t count = size_t(1) << 20;
    std::vector<uint32_t> keys(count);
    std::mt19937 rng(5);
    for (uint32_t& k : keys) k = rng();
    std::vector<uint32_t> order = iota(count);
    BakeStop stop;
    stop.cancel();
    StopPoll poll(&stop);
    EXPECT_FALSE(stoppable_nth_element(order.data(), 0, count / 2, count, ByKey{&keys}, poll));
}

}  // namespace
}  // namespace lc::bake
