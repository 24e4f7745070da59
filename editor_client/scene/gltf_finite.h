#pragma once
// Finiteness of the number arrays a glTF gives (factors, node transforms):
// every one is checked before it reaches the scene.
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <span>

namespace lc::client {

inline bool all_finite(std::span<const double> values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

inline bool all_finite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

}  // namespace lc::client
