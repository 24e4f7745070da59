// Guid text form (Unreal's FGuid::ToString(EGuidFormats::Digits)) and the
// deterministic content hash used for scene and cluster GUIDs.
#include "lightcuts/guid.h"

#include <array>
#include <cstdio>

#include "lightcuts/seeded_mixer.h"

namespace lc {
namespace {

// 64-bit FNV-1a constants; the second lane uses its own offset basis so the
// two halves of the GUID are independent hashes of the same bytes.
constexpr uint64_t kFnvPrime = 0x00000100000001B3ull;
constexpr uint64_t kFnvOffsetLane0 = 0xCBF29CE484222325ull;
constexpr uint64_t kOffsetLane1 = 0x6A09E667F3BCC909ull;      // fractional bits of sqrt(2)
constexpr uint64_t kLane1Multiplier = kGoldenGamma;

uint64_t rotate_left(uint64_t x, int bits) { return (x << bits) | (x >> (64 - bits)); }

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
}

// True when `text` is hex digits in groups of the given lengths, joined by '-'.
bool matches_groups(std::string_view text, std::span<const size_t> groups) {
    size_t pos = 0;
    for (size_t g = 0; g < groups.size(); ++g) {
        if (g > 0) {
            if (pos >= text.size() || text[pos] != '-') return false;
            ++pos;
        }
        for (size_t i = 0; i < groups[g]; ++i, ++pos) {
            if (pos >= text.size() || hex_value(text[pos]) < 0) return false;
        }
    }
    return pos == text.size();
}

}  // namespace

std::string Guid::to_hex() const {
    char text[33];
    std::snprintf(text, sizeof(text), "%08X%08X%08X%08X", a, b, c, d);
    return std::string(text, 32);
}

std::optional<Guid> Guid::parse(std::string_view text) {
    // The three layouts Unreal and our docs print: Digits, DigitsWithHyphens
    // (8-4-4-4-12) and the thesis's four words (8-8-8-8).
    static constexpr std::array<size_t, 1> kDigits{32};
    static constexpr std::array<size_t, 5> kHyphenated{8, 4, 4, 4, 12};
    static constexpr std::array<size_t, 4> kWords{8, 8, 8, 8};
    if (!matches_groups(text, kDigits) && !matches_groups(text, kHyphenated) &&
        !matches_groups(text, kWords)) {
        return std::nullopt;
    }
    std::array<uint32_t, 4> words{};
    size_t digit = 0;
    for (char c : text) {
        if (c == '-') continue;
        uint32_t& word = words[digit / 8];
        word = (word << 4) | static_cast<uint32_t>(hex_value(c));
        ++digit;
    }
    return Guid{words[0], words[1], words[2], words[3]};
}

Guid Guid::from_bytes(std::span<const uint8_t> bytes) {
    // Two independent 64-bit lanes: FNV-1a, and a multiply-rotate hash; both
    // finished with the length so prefixes of each other differ.
    uint64_t lane0 = kFnvOffsetLane0;
    uint64_t lane1 = kOffsetLane1;
    for (uint8_t byte : bytes) {
        lane0 = (lane0 ^ byte) * kFnvPrime;
        lane1 = rotate_left((lane1 ^ byte) * kLane1Multiplier, 29);
    }
    const uint64_t length = bytes.size();
    const uint64_t h0 = mix64(lane0 ^ mix64(length));
    const uint64_t h1 = mix64(lane1 + mix64(length ^ kLane1Multiplier) + h0);
    return Guid{static_cast<uint32_t>(h0 >> 32), static_cast<uint32_t>(h0),
                static_cast<uint32_t>(h1 >> 32), static_cast<uint32_t>(h1)};
}

Guid Guid::combine(const Guid& left, const Guid& right) {
    // A tag byte keeps combine(l, r) apart from from_bytes() of the same 32 bytes.
    std::array<uint8_t, 33> bytes{};
    bytes[0] = 0xC1;
    const std::array<uint32_t, 8> words{left.a,  left.b,  left.c,  left.d,
                                        right.a, right.b, right.c, right.d};
    for (size_t w = 0; w < words.size(); ++w) {
        for (size_t i = 0; i < 4; ++i) {
            bytes[1 + w * 4 + i] = static_cast<uint8_t>(words[w] >> (8 * i));
        }
    }
    return from_bytes(bytes);
}

}  // namespace lc
