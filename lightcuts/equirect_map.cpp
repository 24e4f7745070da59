#include "lightcuts/equirect_map.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "lightcuts/device/equirect_map.glsl.h"

namespace lc {

Status validate_equirect_size(uint64_t width, uint64_t height) {
    const std::string size = std::to_string(width) + " x " + std::to_string(height);
    if (width == 0 || height == 0) return make_error("environment map is " + size + ": it has no texels");
    if (width > kMaxEquirectWidth || height > kMaxEquirectHeight)
        return make_error("environment map is " + size + ": the limit is " + std::to_string(kMaxEquirectWidth) +
                          " x " + std::to_string(kMaxEquirectHeight) + " texels");
    return Ok{};
}

Status validate_equirect_texel(const glm::vec3& radiance, uint32_t x, uint32_t y) {
    for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(radiance[c]) || radiance[c] < 0.0f)
            return make_error("environment texel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                              std::to_string(c) + " is " + std::to_string(radiance[c]) +
                              ": radiance must be finite and non-negative");
    }
    return Ok{};
}

glm::dvec3 equirect_direction(double u, double v, double rotation) {
    const double theta = std::numbers::pi * v;
    const double phi = 2.0 * std::numbers::pi * u + rotation;
    const double sin_theta = std::sin(theta);
    return {sin_theta * std::cos(phi), std::cos(theta), sin_theta * std::sin(phi)};
}

glm::dvec2 equirect_coordinates(const glm::dvec3& direction, double rotation) {
    const glm::dvec3 d = glm::normalize(direction);
    return {equirect::equirect_u(d, rotation), equirect::equirect_v(d)};
}

double equirect_texel_solid_angle(uint32_t y, uint32_t width, uint32_t height) {
    const double theta_top = std::numbers::pi * double(y) / double(height);
    const double theta_bottom = std::numbers::pi * double(y + 1) / double(height);
    return 2.0 * std::numbers::pi / double(width) * (std::cos(theta_top) - std::cos(theta_bottom));
}

glm::vec3 equirect_radiance(const EquirectMap& map, const glm::dvec3& direction, double rotation) {
    if (map.empty()) return glm::vec3(0.0f);
    const glm::dvec2 uv = equirect_coordinates(direction, rotation);
    const auto x = std::min(uint32_t(uv.x * map.width), map.width - 1);
    const auto y = std::min(uint32_t(uv.y * map.height), map.height - 1);
    return map.at(x, y);
}

}  // namespace lc
