// Guid: text form, parsing, and the deterministic content hash.
#include "lightcuts/guid.h"

#include <gtest/gtest.h>

#include <bit>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace lc {
namespace {

std::vector<uint8_t> bytes_of(const std::string& text) {
    return std::vector<uint8_t>(text.begin(), text.end());
}

int differing_bits(const Guid& x, const Guid& y) {
    return std::popcount(x.a ^ y.a) + std::popcount(x.b ^ y.b) + std::popcount(x.c ^ y.c) +
           std::popcount(x.d ^ y.d);
}

TEST(Guid, ToHexIsThirtyTwoUpperCaseDigitsInWordOrder) {
    EXPECT_EQ(Guid{}.to_hex(), "00000000000000000000000000000000");
    EXPECT_EQ((Guid{0x4C696768u, 0x74637574u, 0x73566572u, 0x7369666Eu}.to_hex()),
              "4C69676874637574735665727369666E");
    EXPECT_EQ((Guid{0xABCDEF01u, 0x1u, 0xFFFFFFFFu, 0x10u}.to_hex()),
              "ABCDEF0100000001FFFFFFFF00000010");
}

TEST(Guid, ParseAcceptsDigitsHyphensAndEitherCase) {
    const Guid expected{0x4C696768u, 0x74637574u, 0x73446174u, 0x61475549u};
    EXPECT_EQ(Guid::parse("4C696768746375747344617461475549"), expected);
    EXPECT_EQ(Guid::parse("4c696768746375747344617461475549"), expected);
    EXPECT_EQ(Guid::parse("4C696768-74637574-73446174-61475549"), expected);   // SPEC form
    EXPECT_EQ(Guid::parse("4C696768-7463-7574-7344-617461475549"), expected);  // 8-4-4-4-12
    EXPECT_EQ(Guid::parse("4c696768-7463-7574-7344-617461475549"), expected);
}

TEST(Guid, ParseRejectsEverythingElse) {
    for (const char* bad : {
             "",
             "4C69676874637574734461746147554",      // 31 digits
             "4C6967687463757473446174614755490",    // 33 digits
             "4C69676874637574734461746147554G",     // not hex
             "4C696768-74637574-7344617461475549",   // missing a separator
             "4C69676-874637574-73446174-61475549",  // separator misplaced
             "-4C696768746375747344617461475549",
             "4C696768746375747344617461475549-",
             "{4C696768-7463-7574-7344-617461475549}",
             " 4C696768746375747344617461475549",
             "0x4C696768746375747344617461475549",
             "4C696768--74637574-73446174-614755",
         }) {
        EXPECT_FALSE(Guid::parse(bad).has_value()) << bad;
    }
}

TEST(Guid, ParseInvertsToHex) {
    std::mt19937 rng(7);
    for (int i = 0; i < 1000; ++i) {
        const Guid g{static_cast<uint32_t>(rng()), static_cast<uint32_t>(rng()),
                     static_cast<uint32_t>(rng()), static_cast<uint32_t>(rng())};
        ASSERT_EQ(Guid::parse(g.to_hex()), g);
    }
}

TEST(Guid, FromBytesIsStableAcrossBuildsAndRuns) {
    // Scene GUIDs name channels and dumps: this value must never change silently.
    EXPECT_EQ(Guid::from_bytes(bytes_of("LightcutsDataGUI")).to_hex(),
              "015D456AF5B700332CD2052527D0B97D");
    EXPECT_EQ(Guid::from_bytes(bytes_of("abc")), Guid::from_bytes(bytes_of("abc")));
    EXPECT_FALSE(Guid::from_bytes({}).is_zero());
}

TEST(Guid, FromBytesSeparatesSimilarInputs) {
    // Every string of up to 2 bytes plus 20,000 random 16-byte strings: no collisions.
    std::set<Guid> seen;
    std::vector<std::vector<uint8_t>> inputs{{}};
    for (int x = 0; x < 256; ++x) {
        inputs.push_back({static_cast<uint8_t>(x)});
        for (int y = 0; y < 256; ++y)
            inputs.push_back({static_cast<uint8_t>(x), static_cast<uint8_t>(y)});
    }
    std::mt19937 rng(11);
    for (int i = 0; i < 20000; ++i) {
        std::vector<uint8_t> v(16);
        for (auto& b : v) b = static_cast<uint8_t>(rng());
        inputs.push_back(v);
    }
    for (const auto& input : inputs) seen.insert(Guid::from_bytes(input));
    EXPECT_EQ(seen.size(), inputs.size());
    // Zero bytes of different lengths must differ too (length is hashed).
    EXPECT_NE(Guid::from_bytes(std::vector<uint8_t>(1, 0)),
              Guid::from_bytes(std::vector<uint8_t>(2, 0)));
}

TEST(Guid, FromBytesAvalanches) {
    // Flipping one input bit flips about half of the 128 output bits.
    std::mt19937 rng(3);
    double total = 0.0;
    int samples = 0;
    int worst = 128;
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<uint8_t> v(1 + rng() % 40);
        for (auto& b : v) b = static_cast<uint8_t>(rng());
        const Guid base = Guid::from_bytes(v);
        const size_t bit = rng() % (v.size() * 8);
        v[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
        const int d = differing_bits(base, Guid::from_bytes(v));
        total += d;
        worst = std::min(worst, d);
        ++samples;
    }
    const double mean = total / samples;
    EXPECT_GT(mean, 58.0);
    EXPECT_LT(mean, 70.0);
    EXPECT_GT(worst, 30);
}

TEST(Guid, CombineIsDeterministicAndOrderSensitive) {
    const Guid l = Guid::from_bytes(bytes_of("left"));
    const Guid r = Guid::from_bytes(bytes_of("right"));
    EXPECT_EQ(Guid::combine(l, r), Guid::combine(l, r));
    EXPECT_NE(Guid::combine(l, r), Guid::combine(r, l));
    EXPECT_NE(Guid::combine(l, l), l);
    EXPECT_NE(Guid::combine(l, r), l);
    EXPECT_NE(Guid::combine(l, r), r);
    EXPECT_NE(Guid::combine(Guid{}, Guid{}), Guid{});
    // Combining is not hashing the concatenated words.
    std::vector<uint8_t> concatenated;
    for (uint32_t w : {l.a, l.b, l.c, l.d, r.a, r.b, r.c, r.d}) {
        for (int i = 0; i < 4; ++i) concatenated.push_back(static_cast<uint8_t>(w >> (8 * i)));
    }
    EXPECT_NE(Guid::combine(l, r), Guid::from_bytes(concatenated));
}

TEST(Guid, CombineOfManyPairsHasNoCollisions) {
    std::set<Guid> seen;
    std::vector<Guid> leaves;
    for (uint32_t i = 0; i < 300; ++i) leaves.push_back(Guid{0, 0, 0, i});
    for (const Guid& x : leaves) {
        for (const Guid& y : leaves) seen.insert(Guid::combine(x, y));
    }
    EXPECT_EQ(seen.size(), leaves.size() * leaves.size());
}

TEST(Guid, OrdersByWords) {
    EXPECT_LT((Guid{0, 0, 0, 1}), (Guid{0, 0, 1, 0}));
    EXPECT_LT((Guid{0, 5, 0, 0}), (Guid{1, 0, 0, 0}));
    EXPECT_TRUE(Guid{}.is_zero());
    EXPECT_FALSE((Guid{0, 0, 0, 1}.is_zero()));
}

}  // namespace
}  // namespace lc
