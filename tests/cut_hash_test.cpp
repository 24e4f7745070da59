// The cut hash: each node on a cut adds murmur3's fmix32 of its index + 1,
// so a cut's hash names it whatever order its nodes were found in.
#include <gtest/gtest.h>

#include "lightcuts/cuts/cpu_evaluator.h"

namespace lc::test {
namespace {

TEST(CutHash, IsMurmur3Fmix32OfIndexPlusOne) {
    EXPECT_EQ(cut_hash_term(0), 0x514e28b7u);   // fmix32(1)
    EXPECT_EQ(cut_hash_term(1), 0x30f4c306u);   // fmix32(2)
    EXPECT_EQ(cut_hash_term(0xffffffffu), 0u);  // fmix32(0) = 0
}

}  // namespace
}  // namespace lc::test
