#include "lightcuts/scene_geometry.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace lc {

glm::vec3 triangle_cross(const SurfaceTriangle& t) {
    return glm::cross(t.positions[1] - t.positions[0], t.positions[2] - t.positions[0]);
}

float triangle_area(const SurfaceTriangle& t) { return 0.5f * glm::length(triangle_cross(t)); }

bool is_degenerate(const SurfaceTriangle& t) {
    float area = triangle_area(t);
    return !(area > 0.0f) || !std::isfinite(area);
}

}  // namespace lc
