#include "editor_client/scene/gltf_camera_reader.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <cmath>
#include <numbers>
#include <string>

namespace lc::client {

Status GltfCameraReader::add(int node_index, int camera_index, const glm::dmat4& world, Scene& scene) {
    if (camera_index >= static_cast<int>(model_.cameras.size())) {
        return diagnostics_.fail("node " + std::to_string(node_index) + " uses camera " +
                                 std::to_string(camera_index) + ", which does not exist");
    }
    const tinygltf::Camera& in = model_.cameras[size_t(camera_index)];
    const std::string what = "camera " + std::to_string(camera_index);
    if (in.type != "perspective") {
        diagnostics_.warn(what + " is " + in.type + "; only perspective cameras are loaded");
        return Ok{};
    }
    const double yfov = in.perspective.yfov;
    if (!std::isfinite(yfov) || yfov <= 0.0 || yfov >= std::numbers::pi) {
        diagnostics_.warn(what + ": yfov " + message_number(yfov) + " is outside (0, pi); camera skipped");
        return Ok{};
    }
    const glm::dvec3 eye(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const glm::dvec3 forward = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 up = glm::dmat3(world) * glm::dvec3(0.0, 1.0, 0.0);
    const double flen = glm::length(forward);
    const double ulen = glm::length(up);
    if (!(flen > 1e-12) || !(ulen > 1e-12) || !std::isfinite(flen + ulen) ||
        !std::isfinite(eye.x + eye.y + eye.z)) {
        diagnostics_.warn(what + " on node " + std::to_string(node_index) +
                          " has a degenerate transform; camera skipped");
        return Ok{};
    }
    Camera camera;
    camera.name =
        !in.name.empty() ? in.name : std::string(table_.string(table_.nodes[size_t(node_index)].name));
    camera.eye = glm::vec3(eye);
    camera.up = glm::vec3(up / ulen);
    camera.yfov = float(yfov);
    scene.cameras.push_back(camera);
    forward_.push_back(forward / flen);
    return Ok{};
}

void GltfCameraReader::finish(Scene& scene) const {
    const glm::dvec3 center = (glm::dvec3(scene.bounds_min) + glm::dvec3(scene.bounds_max)) * 0.5;
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        Camera& camera = scene.cameras[i];
        double distance = glm::length(center - glm::dvec3(camera.eye));
        if (!std::isfinite(distance) || distance < 1e-3) distance = 1.0;
        camera.target = glm::vec3(glm::dvec3(camera.eye) + forward_[i] * distance);
    }
}

}  // namespace lc::client
