#include "editor_client/render/sweeps/camera_path.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace lc::client {

std::vector<RenderCamera> orbit_path(const RenderCamera& start, uint32_t frames, float total_degrees) {
    std::vector<RenderCamera> path;
    path.reserve(frames);
    const glm::vec3 axis = glm::normalize(start.up);
    const glm::vec3 offset = start.eye - start.target;
    for (uint32_t i = 0; i < frames; ++i) {
        const float share = frames > 1 ? float(i) / float(frames - 1) : 0.0f;
        const float angle = glm::radians(total_degrees) * share;
        // Rodrigues' rotation of the eye's offset about the up axis.
        const float c = std::cos(angle), s = std::sin(angle);
        const glm::vec3 turned =
            offset * c + glm::cross(axis, offset) * s + axis * glm::dot(axis, offset) * (1.0f - c);
        RenderCamera camera = start;
        camera.eye = start.target + turned;
        path.push_back(camera);
    }
    return path;
}

}  // namespace lc::client
