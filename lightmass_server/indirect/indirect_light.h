#pragma once
// What both indirect solvers produce: bounced light as oriented cosine
// emitters, independent of how the light tree spells them. The bake turns
// each into a tree light marked "indirect"; the tests read them directly.
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace lc::bake {

struct IndirectLight {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  // unit; the emitter lights its front half-space
    glm::vec3 power{0.0f};               // radiant flux leaving the point, linear RGB (W)
    // A radiosity patch: the radius of the disk of its area, which the
    // renderer evaluates instead of clamping it; 0: a VPL, a point.
    float patch_radius = 0.0f;
    // A VPL: the diffuse hit that left it (1: light straight from an emitter);
    // 0 for a patch, whose radiosity holds every bounce. 32 bits: the struct
    // has no padding, so its bytes are the same at any thread count.
    uint32_t bounce = 0;
};
static_assert(sizeof(IndirectLight) == 11 * sizeof(float), "no padding: the tests compare bytes");

// The radius of the disk with the patch's area: the renderer's near-field falloff.
inline float equivalent_disk_radius(float area) {
    return std::sqrt(std::max(area, 0.0f) / std::numbers::pi_v<float>);
}

// A cosine emitter of power P has radiant intensity I(theta) = (P / pi) cos(theta).
inline glm::vec3 intensity_along_normal(const IndirectLight& light) {
    return light.power / std::numbers::pi_v<float>;
}

}  // namespace lc::bake
