#pragma once
// Clicking in the view: the camera ray through a pixel, the nearest surface it
// hits (CPU ray cast over the scene's triangles, so it works in every mode and
// without a G-buffer read-back), and the light nearest to the ray.
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>

#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/scene.h"

namespace lc::client {

struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0};  // unit
};

// The ray through the centre of pixel (x, y) of a width x height image, rows
// from the top, with the renderer's camera conventions (yfov vertical).
Ray camera_ray(const RenderCamera& camera, double x, double y, uint32_t width, uint32_t height);

struct SurfaceHit {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};  // geometric, facing the ray's origin
    double distance = 0.0;
    size_t mesh = 0;
    size_t triangle = 0;
};

// Nearest triangle hit (Moller-Trumbore, double precision); none on a miss.
std::optional<SurfaceHit> pick_surface(const Scene& scene, const Ray& ray);

// Where a light placed by clicking goes: off the surface along its normal, so
// it lights the surface instead of sitting inside it.
glm::vec3 light_position_above(const SurfaceHit& hit, float offset);

// The positioned light whose direction from the ray's origin is within
// `max_angle` radians of the ray, nearest in angle; directional lights have no
// position and are never picked. Lights behind the origin are skipped.
std::optional<size_t> pick_light(const Scene& scene, const Ray& ray, double max_angle);

}  // namespace lc::client
