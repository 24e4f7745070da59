#include "lightcuts/preetham_sky.h"

#include <cstdlib>
#include <cmath>
#include <numbers>
#include <string>

#include "lightcuts/device/preetham_sky.glsl.h"

namespace lc {

bool operator==(const SkyParameters& a, const SkyParameters& b) {
    return a.elevation_deg == b.elevation_deg && a.azimuth_deg == b.azimuth_deg && a.turbidity == b.turbidity;
}

Result<SkyParameters> parse_sky_parameters(std::string_view text) {
    float values[3] = {};
    size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        const size_t comma = i < 2 ? text.find(',', start) : text.size();
        if (comma == std::string_view::npos)
            return make_error("--sky '" + std::string(text) + "': expected ELEVATION,AZIMUTH,TURBIDITY");
        const std::string field(text.substr(start, comma - start));
        char* end = nullptr;
        values[i] = std::strtof(field.c_str(), &end);
        if (field.empty() || end != field.c_str() + field.size())
            return make_error("--sky '" + std::string(text) + "': '" + field + "' is not a number");
        start = comma + 1;
    }
    SkyParameters sky{values[0], values[1], values[2]};
    Status valid = validate_sky_parameters(sky);
    if (!valid) return valid.failure();
    return sky;
}

Status validate_sky_parameters(const SkyParameters& sky) {
    if (!std::isfinite(sky.elevation_deg) || sky.elevation_deg < 0.0f || sky.elevation_deg > 90.0f)
        return make_error("sky: sun elevation " + std::to_string(sky.elevation_deg) +
                          " degrees is outside [0, 90] (the model holds for a sun above the horizon)");
    if (!std::isfinite(sky.azimuth_deg))
        return make_error("sky: sun azimuth " + std::to_string(sky.azimuth_deg) + " is not finite");
    if (!std::isfinite(sky.turbidity) || sky.turbidity < 1.7f || sky.turbidity > 10.0f)
        return make_error("sky: turbidity " + std::to_string(sky.turbidity) +
                          " is outside [1.7, 10], the range the model was fitted over");
    return Ok{};
}

glm::dvec3 sun_direction(const SkyParameters& sky) {
    const double elevation = double(sky.elevation_deg) * std::numbers::pi / 180.0;
    const double azimuth = double(sky.azimuth_deg) * std::numbers::pi / 180.0;
    return {std::cos(elevation) * std::cos(azimuth), std::sin(elevation), std::cos(elevation) * std::sin(azimuth)};
}

glm::dvec3 sky_radiance(const SkyParameters& sky, const glm::dvec3& direction) {
    return sky::preetham_sky_radiance(direction, sun_direction(sky), double(sky.turbidity));
}

glm::dvec3 sun_disc_radiance(const SkyParameters& sky) {
    return sky::preetham_sun_radiance(sun_direction(sky), double(sky.turbidity));
}

double sun_angular_radius() { return sky::kSunAngularRadius; }

EquirectMap rasterize_sky(const SkyParameters& sky, uint32_t width, uint32_t height) {
    EquirectMap map{width, height, std::vector<glm::vec3>(size_t(width) * height)};
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const glm::dvec3 d = equirect_direction((x + 0.5) / width, (y + 0.5) / height, 0.0);
            map.texels[size_t(y) * width + x] = glm::vec3(sky_radiance(sky, d));
        }
    }
    return map;
}

}  // namespace lc
