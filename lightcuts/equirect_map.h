#pragma once
// An environment as an equirectangular (latitude-longitude) image of linear
// RGB radiance, and the one mapping between its texels and world directions
// that the client (loading, background) and the server (sampling) share.
//
// World is glTF's: +Y up. Texel (x, y) covers u in [x, x+1) / W and v in
// [y, y+1) / H; v = 0 is the zenith, v = 1 the nadir. The direction of (u, v)
// is (sin theta cos phi, cos theta, sin theta sin phi) with theta = pi v and
// phi = 2 pi u + rotation (the environment turned about +Y).
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

#include "lightcuts/result.h"

namespace lc {

// Limits (docs/PROTOCOL.md): 8192 x 4096 texels at most, which is an "8k"
// HDRI; the server's sampler keeps three doubles per texel, so this bounds a
// bake's environment at about 800 MiB.
inline constexpr uint32_t kMaxEquirectWidth = 8192;
inline constexpr uint32_t kMaxEquirectHeight = 4096;

struct EquirectMap {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<glm::vec3> texels;  // row-major, row 0 at the zenith

    bool empty() const { return texels.empty(); }
    const glm::vec3& at(uint32_t x, uint32_t y) const { return texels[size_t(y) * width + x]; }
};

// Both dimensions at least 1 and within the limits; the message names them.
Status validate_equirect_size(uint64_t width, uint64_t height);
// Every texel finite and non-negative; the message names the first bad texel.
Status validate_equirect_texel(const glm::vec3& radiance, uint32_t x, uint32_t y);

// (u, v) in [0, 1]^2 to the unit direction; rotation in radians.
glm::dvec3 equirect_direction(double u, double v, double rotation);
// The inverse: u in [0, 1), v in [0, 1].
glm::dvec2 equirect_coordinates(const glm::dvec3& direction, double rotation);
// Solid angle of one texel of row y: (2 pi / W) (cos theta_top - cos theta_bottom).
double equirect_texel_solid_angle(uint32_t y, uint32_t width, uint32_t height);
// Nearest-texel lookup of radiance along a direction.
glm::vec3 equirect_radiance(const EquirectMap& map, const glm::dvec3& direction, double rotation);

}  // namespace lc
