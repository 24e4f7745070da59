#pragma once
// A 128-bit GUID stored as Unreal's FGuid: four 32-bit words A, B, C, D.
#include <array>
#include <compare>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace lc {

struct Guid {
    uint32_t a = 0, b = 0, c = 0, d = 0;

    auto operator<=>(const Guid&) const = default;
    bool is_zero() const { return (a | b | c | d) == 0; }

    // 32 upper-case hex digits, no separators (Unreal's EGuidFormats::Digits).
    std::string to_hex() const;
    // Accepts 32 hex digits with or without '-' separators, either case.
    static std::optional<Guid> parse(std::string_view text);
    // A deterministic GUID from arbitrary bytes (FNV-1a 128-bit style mixing);
    // used for scene GUIDs (stable for a given scene content) and cluster GUIDs.
    static Guid from_bytes(std::span<const uint8_t> bytes);
    // Combines two GUIDs into a third, order-sensitive; used for cluster nodes.
    static Guid combine(const Guid& left, const Guid& right);
};

}  // namespace lc
