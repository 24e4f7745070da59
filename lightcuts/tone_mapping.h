#pragma once
// The tone curve applied to linear HDR radiance for 8-bit output, written once
// here and mirrored in shaders/tone_mapping.glsl (tests compare them):
//   exposure scale, then the ACES filmic fit of Narkowicz (2015), then the
//   sRGB transfer function, then quantisation to 8 bits.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lc::tone {

// ACES filmic fit: x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1].
inline float filmic(float x) {
    x = std::max(x, 0.0f);
    float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    return std::clamp(y, 0.0f, 1.0f);
}

// IEC 61966-2-1 sRGB encoding of a linear value in [0, 1].
inline float srgb_encode(float linear) {
    linear = std::clamp(linear, 0.0f, 1.0f);
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

inline float srgb_decode(float encoded) {
    encoded = std::clamp(encoded, 0.0f, 1.0f);
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// One channel of linear radiance to the 8-bit value the PNG stores.
inline uint8_t to_display_byte(float radiance, float exposure) {
    if (!std::isfinite(radiance)) return 0;
    float encoded = srgb_encode(filmic(radiance * exposure));
    return static_cast<uint8_t>(std::lround(encoded * 255.0f));
}

}  // namespace lc::tone
