#include "lightcuts/occlusion/shadow_ray.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

#include "lightcuts/device/shadow_segment.glsl.h"

namespace lc {

Result<ShadowMode> parse_shadow_mode(std::string_view text) {
    if (std::optional<ShadowMode> mode = value_in(kShadowModeNames, text)) return *mode;
    return make_error("unknown shadow mode '" + std::string(text) + "' (expected " + names_in(kShadowModeNames) +
                      ")");
}

const char* shadow_mode_name(ShadowMode mode) { return name_in(kShadowModeNames, mode); }

float shadow_ray_bias(const Scene& scene) {
    const glm::vec3 lo = scene.bounds_min, hi = scene.bounds_max;
    float extent = glm::length(hi - lo);
    const glm::vec3 far_corner = glm::max(glm::abs(lo), glm::abs(hi));
    float magnitude = std::max({far_corner.x, far_corner.y, far_corner.z});
    if (!std::isfinite(extent)) extent = 0.0f;
    if (!std::isfinite(magnitude)) magnitude = 0.0f;
    // 64 float ulps (2^-23 each) of the largest coordinate: a G-buffer
    // position is rounded to float, and so are the triangles.
    return std::max(1e-4f * extent + 64.0f * 1.1920929e-7f * magnitude, 1e-6f);
}

double light_visibility(const ShadowBvh& occluders, double bias, LightType type,
                        const glm::dvec3& position, const glm::dvec3& direction,
                        const glm::dvec3& x, const glm::dvec3& n) {
    if (occluders.empty()) return 1.0;
    const shading::ShadowSegment s =
        shading::shadow_segment(x, n, type == LightType::kDirectional, position, direction, bias, kShadowRayFar);
    if (!s.traced) return 1.0;
    return occluders.occluded(s.origin, s.direction, s.t_max) ? 0.0 : 1.0;
}

}  // namespace lc
