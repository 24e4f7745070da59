// The seeded mixer against SplitMix64's published reference outputs: GUIDs,
// trees and generated scenes depend on these exact bytes.
#include "lightcuts/seeded_mixer.h"

#include <gtest/gtest.h>

namespace lc {
namespace {

TEST(SeededMixer, SequenceFromSeedZeroMatchesTheReferenceImplementation) {
    SplitMix64 rng(0);
    EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
    EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
    EXPECT_EQ(rng.next(), 0x06C45D188009454Full);
}

TEST(SeededMixer, FinaliserIsTheGeneratorsOutputFunction) {
    EXPECT_EQ(mix64(0), 0u);
    EXPECT_EQ(mix64(1), 0x5692161D100B05E5ull);
    SplitMix64 rng(12345);
    EXPECT_EQ(rng.next(), mix64(12345 + kGoldenGamma));
    EXPECT_EQ(rng.next(), mix64(12345 + 2 * kGoldenGamma));
}

TEST(SeededMixer, UnitIntervalKeepsTheTop53Bits) {
    EXPECT_EQ(unit_interval(0), 0.0);
    EXPECT_EQ(unit_interval(uint64_t(1) << 63), 0.5);
    EXPECT_LT(unit_interval(~uint64_t(0)), 1.0);
    EXPECT_EQ(unit_interval(~uint64_t(0)), 1.0 - 0x1.0p-53);
    EXPECT_EQ(unit_interval(0x7FF), 0.0);  // the low 11 bits are dropped
}

}  // namespace
}  // namespace lc
