#pragma once
// The paper's automatic clamp solved exactly for a set of indirect lights:
// each light at min(L_i, t) per channel, t the largest root of
// t = ratio x (others + sum_i min(L_i, t)). The CPU's reference (every leaf
// of the tree) uses it; the GPU's reference reaches the same root over passes
// (device/indirect_clamp.glsl.h), the cuts approximate it from their two
// largest lights.
#include <glm/vec3.hpp>

#include <span>

namespace lc {

struct ExactClamp {
    glm::dvec3 threshold{0.0};  // t per channel
    glm::dvec3 radiance{0.0};   // others plus every light at min(L_i, t)
    glm::dvec3 removed{0.0};    // what the clamp took, per channel
};

// The largest root of one channel, from the lights' values in any order.
double exact_clamp_threshold(double others, std::span<const double> lights, double ratio);

ExactClamp exact_indirect_clamp(const glm::dvec3& others, std::span<const glm::dvec3> lights, double ratio);

}  // namespace lc
