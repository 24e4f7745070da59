#pragma once
// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number
// generators", 2014): the one seeded mixer behind GUID hashing, the server's
// counter-based representative draws and the procedural scene layouts. Tiny,
// and identical on every platform (the standard distributions are not), so
// GUIDs, trees and generated scenes are the same bytes everywhere.
#include <cstdint>

namespace lc {

// 2^64 / golden ratio: SplitMix64's state increment.
inline constexpr uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;

// SplitMix64's finaliser: a bijection that spreads every input bit over the word.
constexpr uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 27;
    x *= 0x94D049BB133111EBull;
    x ^= x >> 31;
    return x;
}

// The top 53 bits of `bits` as a double, uniform in [0, 1).
constexpr double unit_interval(uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

// The sequential generator: mix64 of a state advanced by kGoldenGamma.
class SplitMix64 {
public:
    explicit constexpr SplitMix64(uint64_t state) : state_(state) {}
    constexpr uint64_t next() { return mix64(state_ += kGoldenGamma); }
    constexpr double uniform() { return unit_interval(next()); }

private:
    uint64_t state_;
};

}  // namespace lc
