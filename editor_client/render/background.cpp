#include "editor_client/render/background.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <numbers>

#include "editor_client/render/passes/gbuffer_pass.h"
#include "lightcuts/preetham_sky.h"

namespace lc::client {
namespace {

// The eye rays as an affine function of the pixel: the clip-space line
// through a point of the image, from the near plane (depth 0) to the far
// plane (depth 1), is a world-space eye ray; both planes map affinely under
// perspective, so the ray at pixel (x, y) is r0 + x dx + y dy.
void set_eye_rays(GpuBackground& out, const glm::mat4& view_proj, uint32_t width, uint32_t height) {
    const glm::dmat4 clip_to_world = glm::inverse(glm::dmat4(view_proj));
    auto ray = [&](double x, double y) {
        const glm::dvec2 ndc(2.0 * x / double(width) - 1.0, 2.0 * y / double(height) - 1.0);
        const glm::dvec4 near_point = clip_to_world * glm::dvec4(ndc, 0.0, 1.0);
        const glm::dvec4 far_point = clip_to_world * glm::dvec4(ndc, 1.0, 1.0);
        return glm::dvec3(far_point) / far_point.w - glm::dvec3(near_point) / near_point.w;
    };
    const glm::dvec3 origin = ray(0.0, 0.0);
    const glm::dvec3 step_x = ray(1.0, 0.0) - origin;
    const glm::dvec3 step_y = ray(0.0, 1.0) - origin;
    // Lengths do not matter (the shader normalises): keep the floats near 1.
    const double scale = 1.0 / glm::length(ray(0.5 * width, 0.5 * height));
    out.ray_at_origin = glm::vec3(origin * scale);
    out.ray_step_x = glm::vec3(step_x * scale);
    out.ray_step_y = glm::vec3(step_y * scale);
}

}  // namespace

glm::dvec3 background_eye_ray(const GpuBackground& background, double x, double y) {
    return glm::normalize(glm::dvec3(background.ray_at_origin) + x * glm::dvec3(background.ray_step_x) +
                          y * glm::dvec3(background.ray_step_y));
}

glm::dvec3 environment_radiance(const Environment& environment, const glm::dvec3& direction) {
    glm::dvec3 radiance(0.0);
    if (environment.has_sky()) {
        const SkyParameters& sky = *environment.sky;
        radiance = sky_radiance(sky, direction);
        if (glm::dot(direction, sun_direction(sky)) >= std::cos(sun_angular_radius()))
            radiance += sun_disc_radiance(sky);
    } else if (environment.has_map()) {
        const double rotation = double(environment.rotation_deg) * std::numbers::pi / 180.0;
        radiance = glm::dvec3(equirect_radiance(environment.map, direction, rotation));
    }
    return radiance * double(environment.intensity);
}

GpuBackground make_gpu_background(const Environment* environment, const RenderSettings& settings,
                                  uint32_t width, uint32_t height, const glm::vec3& bounds_min,
                                  const glm::vec3& bounds_max) {
    GpuBackground out;
    if (environment == nullptr) return out;
    set_eye_rays(out, eye_ray_view_projection(settings, width, height, bounds_min, bounds_max), width,
                 height);
    out.intensity = environment->intensity;
    if (environment->has_sky()) {
        const SkyParameters& sky = *environment->sky;
        out.kind = kBackgroundSky;
        out.sun_direction = glm::vec3(sun_direction(sky));
        out.sun_radiance = glm::vec3(sun_disc_radiance(sky));
        out.sun_cos_radius = float(std::cos(sun_angular_radius()));
        out.turbidity = sky.turbidity;
    } else if (environment->has_map()) {
        out.kind = kBackgroundMap;
        out.rotation = float(double(environment->rotation_deg) * std::numbers::pi / 180.0);
        out.map_width = environment->map.width;
        out.map_height = environment->map.height;
    }
    return out;
}

}  // namespace lc::client
