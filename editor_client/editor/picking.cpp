#include "editor_client/editor/picking.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace lc::client {

Ray camera_ray(const RenderCamera& camera, double x, double y, uint32_t width, uint32_t height) {
    const double w = std::max<uint32_t>(width, 1), h = std::max<uint32_t>(height, 1);
    const glm::dvec3 eye(camera.eye);
    const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double tan_half = std::tan(0.5 * double(camera.yfov));
    // Normalised device coordinates, x right, y down (Vulkan), pixel centres.
    const double ndc_x = 2.0 * (x + 0.5) / w - 1.0;
    const double ndc_y = 2.0 * (y + 0.5) / h - 1.0;
    const glm::dvec3 d = forward + right * (ndc_x * tan_half * (w / h)) - up * (ndc_y * tan_half);
    return Ray{eye, glm::normalize(d)};
}

std::optional<SurfaceHit> pick_surface(const Scene& scene, const Ray& ray) {
    std::optional<SurfaceHit> best;
    double best_t = std::numeric_limits<double>::infinity();
    constexpr double kEpsilon = 1e-12;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
            if (i0 >= mesh.positions.size() || i1 >= mesh.positions.size() ||
                i2 >= mesh.positions.size())
                continue;
            const glm::dvec3 p0(mesh.positions[i0]);
            const glm::dvec3 e1 = glm::dvec3(mesh.positions[i1]) - p0;
            const glm::dvec3 e2 = glm::dvec3(mesh.positions[i2]) - p0;
            // Moller-Trumbore: solve origin + t d = p0 + u e1 + v e2.
            const glm::dvec3 pvec = glm::cross(ray.direction, e2);
            const double det = glm::dot(e1, pvec);
            if (std::abs(det) < kEpsilon) continue;  // parallel or degenerate
            const double inv_det = 1.0 / det;
            const glm::dvec3 tvec = ray.origin - p0;
            const double u = glm::dot(tvec, pvec) * inv_det;
            if (u < 0.0 || u > 1.0) continue;
            const glm::dvec3 qvec = glm::cross(tvec, e1);
            const double v = glm::dot(ray.direction, qvec) * inv_det;
            if (v < 0.0 || u + v > 1.0) continue;
            const double dist = glm::dot(e2, qvec) * inv_det;
            if (dist <= 1e-9 || dist >= best_t) continue;
            best_t = dist;
            glm::dvec3 normal = glm::normalize(glm::cross(e1, e2));
            if (glm::dot(normal, ray.direction) > 0.0) normal = -normal;
            best = SurfaceHit{glm::vec3(ray.origin + ray.direction * dist), glm::vec3(normal), dist,
                              m, t / 3};
        }
    }
    return best;
}

glm::vec3 light_position_above(const SurfaceHit& hit, float offset) {
    return hit.position + hit.normal * offset;
}

std::optional<size_t> pick_light(const Scene& scene, const Ray& ray, double max_angle) {
    std::optional<size_t> best;
    double best_cos = std::cos(max_angle);
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const SceneLight& light = scene.lights[i];
        if (light.type == LightType::kDirectional) continue;
        const glm::dvec3 to_light = glm::dvec3(light.position) - ray.origin;
        const double distance = glm::length(to_light);
        if (distance <= 0.0) continue;
        const double cos_angle = glm::dot(to_light, ray.direction) / distance;
        if (cos_angle > best_cos) {  // in front and nearer to the ray than any so far
            best_cos = cos_angle;
            best = i;
        }
    }
    return best;
}

}  // namespace lc::client
