#pragma once
// The C++ face of the Preetham sun and sky (lightcuts/device/preetham_sky.glsl.h):
// the parameters as --sky gives them, the sun's place, and the sky rasterised
// into an equirectangular map for the server's sampler.
#include <glm/vec3.hpp>

#include <cstdint>
#include <string_view>

#include "lightcuts/equirect_map.h"
#include "lightcuts/result.h"

namespace lc {

struct SkyParameters {
    float elevation_deg = 45.0f;  // of the sun above the horizon, [0, 90]
    float azimuth_deg = 0.0f;     // phi of the sun, as in equirect_map.h
    float turbidity = 3.0f;       // [1.7, 10], the range Preetham fitted
};

bool operator==(const SkyParameters& a, const SkyParameters& b);

// "ELEVATION,AZIMUTH,TURBIDITY" in degrees, degrees and the turbidity.
Result<SkyParameters> parse_sky_parameters(std::string_view text);
Status validate_sky_parameters(const SkyParameters& sky);

// Unit direction towards the sun's centre.
glm::dvec3 sun_direction(const SkyParameters& sky);
// linear sRGB, kcd/m^2: the sky without the sun, and the inside of the sun's disc.
glm::dvec3 sky_radiance(const SkyParameters& sky, const glm::dvec3& direction);
glm::dvec3 sun_disc_radiance(const SkyParameters& sky);
double sun_angular_radius();
// The sky without the sun at each texel's centre (no rotation).
EquirectMap rasterize_sky(const SkyParameters& sky, uint32_t width, uint32_t height);

}  // namespace lc
