#pragma once
// The shading model, written once for the CPU evaluator (double) and mirrored
// field for field in shaders/common_lighting.glsl (float). Tests compare them.
//
// Radiance leaving a surface point x with normal n towards the camera, from one
// light:  L = f_r * E,  E = I * color * G * V (V: shadow_ray.h; f_r: material_model.h).
//   point/spot:  G = window(d, range) * max(cos_theta, 0) / max(d^2, kMinDistance^2)
//                window(d, range) = clamp(1 - (d/range)^4, 0, 1)^2 (KHR_lights_punctual)
//                spot: G *= clamp((cos_s - cos_outer) / max(cos_inner - cos_outer, 1e-4), 0, 1)^2
//   directional: G = max(cos_theta, 0) (intensity in lux)
//   f_r = diffuse albedo / pi + the glossy lobe (material_model.h)
#include <algorithm>
#include <cmath>
#include <numbers>

namespace lc::shading {

// Keeps the inverse-square law finite at a shading point that sits on a light.
inline constexpr double kMinDistance = 1e-3;
inline constexpr double kSpotMinCosDelta = 1e-4;

template <typename T>
T range_window(T distance, T range) {
    if (range <= T(0)) return T(1);
    T ratio = distance / range;
    T r2 = ratio * ratio;
    T w = std::clamp(T(1) - r2 * r2, T(0), T(1));
    return w * w;
}

template <typename T>
T inverse_square(T distance_squared) {
    T min2 = T(kMinDistance * kMinDistance);
    return T(1) / std::max(distance_squared, min2);
}

template <typename T>
T spot_attenuation(T cos_spot, T cos_inner, T cos_outer) {
    T scale = T(1) / std::max(cos_inner - cos_outer, T(kSpotMinCosDelta));
    T a = std::clamp((cos_spot - cos_outer) * scale, T(0), T(1));
    return a * a;
}

template <typename T>
T lambert(T albedo) {
    return albedo / T(std::numbers::pi);
}

}  // namespace lc::shading
