#include "lightmass_server/indirect/patch_lights.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace lc::bake {
namespace {

// How high above the patch the contact probes run, as a share of its size:
// clear of its own plane at float precision, low enough to meet a wall's foot.
constexpr float kProbeHeight = 0.02f;

void append_triangle(const glm::vec3 (&v)[3], glm::vec3 normal, glm::dvec3 reflected, float epsilon, int levels,
                     std::vector<IndirectLight>& out) {
    if (levels <= 0) {
        const float area = 0.5f * glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
        const glm::vec3 centre = (v[0] + v[1] + v[2]) / 3.0f;
        // Just off the surface, so the renderer's shadow rays leave it.
        out.push_back({centre + normal * epsilon, normal, glm::vec3(reflected * double(area)), equivalent_disk_radius(area)});
        return;
    }
    const glm::vec3 m01 = 0.5f * (v[0] + v[1]), m12 = 0.5f * (v[1] + v[2]), m20 = 0.5f * (v[2] + v[0]);
    const glm::vec3 parts[4][3] = {{v[0], m01, m20}, {m01, v[1], m12}, {m20, m12, v[2]}, {m01, m12, m20}};
    for (const auto& part : parts) append_triangle(part, normal, reflected, epsilon, levels - 1, out);
}

}  // namespace

bool near_contact(const Patch& p, const RayCaster& caster, float epsilon) {
    const glm::vec3(&v)[3] = p.vertices;
    const float size = std::max({glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2])});
    const glm::vec3 lift = p.normal * std::max(kProbeHeight * size, 2.0f * epsilon);
    const glm::vec3 origin = p.centre + lift;
    const glm::vec3 aims[6] = {v[0], v[1], v[2], 0.5f * (v[0] + v[1]), 0.5f * (v[1] + v[2]), 0.5f * (v[2] + v[0])};
    for (const glm::vec3& aim : aims) {
        // Twice as far as the aim: to the neighbouring patches' centres and past.
        if (caster.occluded(origin, 2.0f * (aim - p.centre), 0.0f, 1.0f)) return true;
    }
    return false;
}

void append_patch_lights(const Patch& p, glm::dvec3 reflected, float epsilon, int levels,
                         std::vector<IndirectLight>& out) {
    append_triangle(p.vertices, p.normal, reflected, epsilon, levels, out);
}

}  // namespace lc::bake
